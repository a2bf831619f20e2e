//! Closed-form flight of the main mass: the free damped oscillator of paper Eq 25,
//! `M·x'' + C·x' + K·x = 0`, in all three damping regimes (the ball, `m·y'' = 0`, moves linearly).
//!
//! With `γ = C/(2M)` (1/s), `ω0² = K/M` (1/s²) and `D = γ² − ω0²`, every solution is
//! `x(t) = e^{−γt}·[x0·c(t) + (v0 + γ·x0)·S(t)]`, `x'(t) = e^{−γt}·[v0·c(t) − (ω0²·x0 + γ·v0)·S(t)]`
//! where `c' = D·S`, `S' = c`, `c(0) = 1`, `S(0) = 0`:
//! `c = cos ωd t`, `S = sin(ωd t)/ωd` (underdamped, `ωd² = −D`); `c = 1`, `S = t` (critical, which
//! includes `K = C = 0`: `x = x0 + v0·t`); `c = cosh st`, `S = sinh(st)/s` (overdamped, `s² = D`,
//! which includes `K = 0 < C`). Units: metres, seconds.

/// The damping regime of the free oscillator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Regime {
    /// `γ < ω0`: damped frequency `wd` (rad/s), phase lag `psi = atan2(wd, γ)` of each derivative.
    Under { wd: f64, psi: f64 },
    /// `γ = ω0` (also `K = C = 0`).
    Critical,
    /// `γ > ω0`: `s = sqrt(γ² − ω0²)` (1/s).
    Over { s: f64 },
}

/// The free oscillator `x'' + 2γ·x' + ω0²·x = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Oscillator {
    /// `γ = C/(2M)` (1/s).
    pub gamma: f64,
    /// `ω0² = K/M` (1/s²).
    pub w0sq: f64,
    pub regime: Regime,
}

impl Oscillator {
    /// The oscillator of main mass `big_m` (kg), stiffness `k` (N/m) and viscous damping `c` (N·s/m).
    pub fn new(big_m: f64, k: f64, c: f64) -> Self {
        let gamma = c / (2.0 * big_m);
        let w0sq = k / big_m;
        let disc = gamma * gamma - w0sq;
        let regime = if disc < 0.0 {
            let wd = (-disc).sqrt();
            Regime::Under { wd, psi: wd.atan2(gamma) }
        } else if disc == 0.0 {
            Regime::Critical
        } else {
            Regime::Over { s: disc.sqrt() }
        };
        Oscillator { gamma, w0sq, regime }
    }

    /// `(e^{−γt}·c(t), e^{−γt}·S(t))`, evaluated without overflow or cancellation.
    #[inline]
    pub fn basis(&self, t: f64) -> (f64, f64) {
        match self.regime {
            Regime::Under { wd, .. } => {
                let e = (-self.gamma * t).exp();
                let (sn, cs) = (wd * t).sin_cos();
                (e * cs, e * sn / wd)
            }
            Regime::Critical => {
                let e = (-self.gamma * t).exp();
                (e, e * t)
            }
            Regime::Over { s } => {
                let ep = ((s - self.gamma) * t).exp();
                let em = (-(s + self.gamma) * t).exp();
                let st = s * t;
                let sh = if st.abs() < 1e-3 {
                    let q = st * st;
                    (-self.gamma * t).exp() * t * (1.0 + q / 6.0 * (1.0 + q / 20.0 * (1.0 + q / 42.0)))
                } else {
                    (ep - em) / (2.0 * s)
                };
                (0.5 * (ep + em), sh)
            }
        }
    }

    /// Position and velocity `(x, x')` a time `t` (s) after the state `(x0, v0)`.
    #[inline]
    pub fn advance(&self, x0: f64, v0: f64, t: f64) -> (f64, f64) {
        let (c, s) = self.basis(t);
        (x0 * c + (v0 + self.gamma * x0) * s, v0 * c - (self.w0sq * x0 + self.gamma * v0) * s)
    }

    /// Acceleration `x''` (m/s²) at the state `(x, v)`.
    #[inline]
    pub fn accel(&self, x: f64, v: f64) -> f64 {
        -2.0 * self.gamma * v - self.w0sq * x
    }

    /// A bound on `|x''|` over all future free motion from `(x, v)`: the oscillator energy
    /// `x'² + ω0²·x²` does not grow in flight, so `|x'| ≤ V` and `ω0·|x| ≤ V` with
    /// `V = sqrt(x'² + ω0²x²)`, hence `|x''| ≤ (2γ + ω0)·V` (m/s²).
    pub fn accel_bound(&self, x: f64, v: f64) -> f64 {
        let w0 = self.w0sq.sqrt();
        (2.0 * self.gamma + w0) * (v * v + self.w0sq * x * x).sqrt()
    }
}

/// Calls `f(t)` for each `t ∈ (0, t_end]` with `ωd·t = base + k·period`, k integer, in order.
#[inline]
fn periodic_times(base: f64, period: f64, wd: f64, t_end: f64, mut f: impl FnMut(f64)) {
    // Smallest k with (base + k·period) > 0.
    let mut k = (-base / period).floor() + 1.0;
    let mut n = 0;
    loop {
        let t = (base + k * period) / wd;
        if t > t_end || n > 1_000_000 {
            break;
        }
        if t > 0.0 {
            f(t);
        }
        k += 1.0;
        n += 1;
    }
}

/// An event of the main mass's free motion that the recorder needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FlightEvent {
    /// A local maximum of `x`.
    MaxX,
    /// An upward zero crossing of `x`.
    UpCross,
    /// A zero of `x''` (an extremum of `x'`).
    ZeroAccel,
}

impl Oscillator {
    /// Calls `f(kind, t)` in time order for the events of the free motion from `(x0, v0)` over
    /// `t ∈ (0, t_end]`: local maxima of `x`, upward zero crossings of `x`, zeros of `x''`.
    pub fn for_each_event(&self, x0: f64, v0: f64, t_end: f64, mut f: impl FnMut(FlightEvent, f64)) {
        match self.regime {
            Regime::Under { wd, psi } => {
                // x = R·e^{−γt}·cos θ, θ = ωd·t − φ; x' = −R·ω0·e^{−γt}·cos(θ − ψ);
                // x'' = R·ω0²·e^{−γt}·cos(θ − 2ψ).
                let a = x0;
                let b = (v0 + self.gamma * x0) / wd;
                if a == 0.0 && b == 0.0 {
                    return;
                }
                let phi = b.atan2(a);
                let two_pi = 2.0 * std::f64::consts::PI;
                let half_pi = 0.5 * std::f64::consts::PI;
                // Up-crossings: θ = −π/2 + 2kπ; maxima: θ − ψ = −π/2 + 2kπ (cos(θ−ψ) − → +).
                // Merge the two periodic sequences (both with period 2π/ωd) in time order.
                let up_base = -half_pi + phi;
                let max_base = -half_pi + psi + phi;
                let mut up_k = (-up_base / two_pi).floor() + 1.0;
                let mut max_k = (-max_base / two_pi).floor() + 1.0;
                let mut guard = 0;
                loop {
                    let tu = (up_base + up_k * two_pi) / wd;
                    let tm = (max_base + max_k * two_pi) / wd;
                    let (kind, t) = if tu <= tm { (FlightEvent::UpCross, tu) } else { (FlightEvent::MaxX, tm) };
                    if t > t_end || guard > 1_000_000 {
                        break;
                    }
                    if t > 0.0 {
                        f(kind, t);
                    }
                    if kind == FlightEvent::UpCross {
                        up_k += 1.0;
                    } else {
                        max_k += 1.0;
                    }
                    guard += 1;
                }
                // Zeros of x'': θ − 2ψ = π/2 + kπ.
                periodic_times(half_pi + 2.0 * psi + phi, std::f64::consts::PI, wd, t_end, |t| {
                    f(FlightEvent::ZeroAccel, t);
                });
            }
            Regime::Critical | Regime::Over { .. } => {
                // At most one zero each of x, x', x'' (two-exponential or (a+bt)e^{rt} form):
                // a sign change over the interval brackets it.
                let xv = |t: f64| self.advance(x0, v0, t);
                let (x1, v1) = xv(t_end);
                let a0 = self.accel(x0, v0);
                let a1 = self.accel(x1, v1);
                let mut evs: [(FlightEvent, f64); 3] = [(FlightEvent::MaxX, f64::INFINITY); 3];
                if x0 <= 0.0 && x1 > 0.0 {
                    evs[0] = (FlightEvent::UpCross, bisect(|t| xv(t).0, t_end));
                }
                if v0 > 0.0 && v1 <= 0.0 {
                    evs[1] = (FlightEvent::MaxX, bisect(|t| xv(t).1, t_end));
                }
                if (a0 > 0.0 && a1 < 0.0) || (a0 < 0.0 && a1 > 0.0) {
                    evs[2] = (
                        FlightEvent::ZeroAccel,
                        bisect(
                            |t| {
                                let (x, v) = xv(t);
                                self.accel(x, v)
                            },
                            t_end,
                        ),
                    );
                }
                evs.sort_by(|p, q| p.1.total_cmp(&q.1));
                for (k, t) in evs {
                    if t.is_finite() && t > 0.0 && t <= t_end {
                        f(k, t);
                    }
                }
            }
        }
    }
}

/// The root of `g` in `(0, t_end]` given a sign change between the ends (bisection to ~1 ulp).
fn bisect(g: impl Fn(f64) -> f64, t_end: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, t_end);
    let g_lo = g(lo);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let gm = g(mid);
        if (gm > 0.0) == (g_lo > 0.0) && gm != 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: RK4 with a fine step on x'' = −2γx' − ω0²x.
    fn rk4(o: &Oscillator, x0: f64, v0: f64, t: f64) -> (f64, f64) {
        let n = 20_000;
        let h = t / f64::from(n);
        let f = |x: f64, v: f64| (v, o.accel(x, v));
        let (mut x, mut v) = (x0, v0);
        for _ in 0..n {
            let (k1x, k1v) = f(x, v);
            let (k2x, k2v) = f(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
            let (k3x, k3v) = f(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
            let (k4x, k4v) = f(x + h * k3x, v + h * k3v);
            x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
        (x, v)
    }

    fn check(big_m: f64, k: f64, c: f64, want: fn(&Regime) -> bool) {
        let o = Oscillator::new(big_m, k, c);
        assert!(want(&o.regime), "{:?}", o.regime);
        for &(x0, v0, t) in &[(0.0, 2.0, 0.37), (0.013, -0.7, 1.3), (-0.02, 0.1, 0.05)] {
            let (x, v) = o.advance(x0, v0, t);
            let (xr, vr) = rk4(&o, x0, v0, t);
            let sc = x0.abs() + v0.abs();
            assert!((x - xr).abs() < 1e-10 * sc && (v - vr).abs() < 1e-9 * sc, "{x} {xr} {v} {vr}");
        }
    }

    #[test]
    fn underdamped_matches_ode() {
        check(0.5, 500.0, 0.05, |r| matches!(r, Regime::Under { .. }));
        check(0.5, 500.0, 25.0, |r| matches!(r, Regime::Under { .. }));
    }

    #[test]
    fn critical_matches_ode() {
        // C = 2·sqrt(K·M) exactly: K = 2, M = 0.5 → C = 2.
        check(0.5, 2.0, 2.0, |r| *r == Regime::Critical);
        check(0.5, 0.0, 0.0, |r| *r == Regime::Critical);
    }

    #[test]
    fn overdamped_matches_ode() {
        check(0.5, 500.0, 80.0, |r| matches!(r, Regime::Over { .. }));
        check(0.5, 0.0, 3.0, |r| matches!(r, Regime::Over { .. }));
        // Barely overdamped: the series branch of sinh.
        check(0.5, 2.0, 2.0 + 1e-9, |r| matches!(r, Regime::Over { .. }));
    }

    #[test]
    fn events_are_true_extrema() {
        for &(k, c) in &[(500.0, 0.05), (500.0, 80.0), (2.0, 2.0)] {
            let o = Oscillator::new(0.5, k, c);
            let (x0, v0) = (-0.001, 0.9);
            let mut seen = 0;
            o.for_each_event(x0, v0, 1.0, |kind, t| {
                seen += 1;
                let (x, v) = o.advance(x0, v0, t);
                match kind {
                    FlightEvent::MaxX => assert!(v.abs() < 1e-12, "v {v}"),
                    FlightEvent::UpCross => assert!(x.abs() < 1e-14, "x {x}"),
                    FlightEvent::ZeroAccel => assert!(o.accel(x, v).abs() < 1e-9, "a"),
                }
            });
            assert!(seen > 0);
        }
    }
}
