//! The structure alone, struck once: f_n, ζ, K and C from a measured free decay
//! (docs/model.md §13.1).
//!
//! The model of the measured signal s(t), whatever its kind:
//!
//! `s(t) = e^{−σ(t−t₀)}·(A·cos ω_d(t−t₀) + B·sin ω_d(t−t₀)) + o + d·(t−t₀)`
//!
//! the free decay of Eq 25 (M·x'' + C·x' + K·x = 0, underdamped) plus the sensor's DC offset o
//! and a linear drift d. A velocity or an acceleration is the model's own first or second
//! derivative, which is again a decaying sine of the same σ and ω_d (other A, B): the model is
//! differentiated, the data are never integrated, so an offset or a drift of an accelerometer
//! stays an offset and a drift. From σ and ω_d: ω_n = √(ω_d² + σ²), f_n = ω_n/2π, ζ = σ/ω_n,
//! K = M·ω_n², C = 2·M·σ, with M the main mass the user gives.
//!
//! The start: the frequency from the cycles' zero crossings refined to the peak of the
//! periodogram (the data's own Fourier sum on their own, possibly uneven, times), σ from the
//! log decrement (the straight line through the logarithms of the cycle amplitudes), then
//! A, B, o and d by linear least squares. The six parameters are then refined together by
//! Levenberg–Marquardt (the `levenberg-marquardt` crate on nalgebra, a port of MINPACK's
//! lmder; Moré 1978) with the analytic Jacobian. Standard errors come from the Jacobian at the
//! optimum scaled by the residual variance, cov = s²·(JᵀJ)⁻¹ with s² = RSS/(n − 6), carried to
//! f_n, ζ, K and C by their first derivatives (the delta method).

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn, OMatrix, OVector, U6};
use serde::{Deserialize, Serialize};

use super::{bad, look, window_amplitude, Quantity, Series};
use crate::error::ThudError;

use std::f64::consts::PI;

/// The fitted structure with standard errors, as `thud fit structure --json` prints it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StructureFit {
    /// Undamped natural frequency f_n = ω_n/2π (Hz).
    pub f_n_hz: f64,
    pub f_n_hz_stderr: f64,
    /// Damping ratio ζ = σ/ω_n.
    pub zeta: f64,
    pub zeta_stderr: f64,
    /// Stiffness K = M·ω_n² (N/m).
    pub k_n_m: f64,
    pub k_n_m_stderr: f64,
    /// Viscous damping C = 2·M·σ (N·s/m).
    pub c_n_s_m: f64,
    pub c_n_s_m_stderr: f64,
    /// The main mass M given (kg).
    pub main_mass_kg: f64,
    /// Root mean square of data − model (in the signal's unit, [`StructureFit::unit`]).
    pub residual_rms: f64,
    /// The signal's unit ("m", "m/s", "m/s^2").
    pub unit: String,
    /// Whether Levenberg–Marquardt converged; when false the numbers are its best estimate.
    pub converged: bool,
    /// How the optimiser ended, in words.
    pub termination: String,
    /// Samples and whole cycles in the record.
    pub samples: usize,
    pub cycles: f64,
    /// The start: the spectrum peak (Hz) and the log decrement's ζ.
    pub start_f_hz: f64,
    pub start_zeta: f64,
    /// The fitted model (for plotting): s(t) = e^{−στ}(A cos ω_d τ + B sin ω_d τ) + o + d·τ,
    /// τ = t − t0.
    pub model: DecayModel,
}

/// The fitted free decay with offset and drift, in the signal's unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DecayModel {
    /// Time origin t0 (s): the record's first sample.
    pub t0_s: f64,
    /// Decay rate σ = ζ·ω_n (1/s).
    pub sigma_1_s: f64,
    /// Damped angular frequency ω_d (rad/s).
    pub omega_d_rad_s: f64,
    pub a: f64,
    pub b: f64,
    /// DC offset o and drift d (per s).
    pub offset: f64,
    pub drift_per_s: f64,
}

impl DecayModel {
    /// The model at time `t_s` (s).
    #[must_use]
    pub fn at(&self, t_s: f64) -> f64 {
        let tau = t_s - self.t0_s;
        let (s, c) = (self.omega_d_rad_s * tau).sin_cos();
        (-self.sigma_1_s * tau).exp() * (self.a * c + self.b * s) + self.offset + self.drift_per_s * tau
    }
}

/// The least-squares problem on normalised time u = (t − t0)/T ∈ [0, 1] and a signal scaled
/// to unit rms, so that the six parameters are all of order one: p = [σT, ω_dT, A, B, o, d·T].
struct Problem {
    u: Vec<f64>,
    y: Vec<f64>,
    p: OVector<f64, U6>,
}

impl Problem {
    fn parts(&self, u: f64) -> (f64, f64, f64) {
        let e = (-self.p[0] * u).exp();
        let (s, c) = (self.p[1] * u).sin_cos();
        (e, c, s)
    }
}

impl LeastSquaresProblem<f64, Dyn, U6> for Problem {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, U6>;
    type ParameterStorage = Owned<f64, U6>;

    fn set_params(&mut self, x: &OVector<f64, U6>) {
        self.p.copy_from(x);
    }

    fn params(&self) -> OVector<f64, U6> {
        self.p
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let p = &self.p;
        Some(DVector::from_iterator(
            self.u.len(),
            self.u.iter().zip(&self.y).map(|(&u, &y)| {
                let (e, c, s) = self.parts(u);
                e * (p[2] * c + p[3] * s) + p[4] + p[5] * u - y
            }),
        ))
    }

    fn jacobian(&self) -> Option<OMatrix<f64, Dyn, U6>> {
        let p = &self.p;
        let mut j = OMatrix::<f64, Dyn, U6>::zeros(self.u.len());
        for (i, &u) in self.u.iter().enumerate() {
            let (e, c, s) = self.parts(u);
            j[(i, 0)] = -u * e * (p[2] * c + p[3] * s);
            j[(i, 1)] = u * e * (-p[2] * s + p[3] * c);
            j[(i, 2)] = e * c;
            j[(i, 3)] = e * s;
            j[(i, 4)] = 1.0;
            j[(i, 5)] = u;
        }
        Some(j)
    }
}

/// The periodogram's peak (Hz) of the detrended signal near `f0` (± 30 %, 241 trial
/// frequencies, then a parabola through the best three): the data's Fourier sum on their own
/// times, each sample weighted by its share of the record (trapezoid), so uneven sampling needs
/// no resampling.
fn spectrum_peak(t: &[f64], y: &[f64], f0: f64) -> f64 {
    let n = t.len();
    let w: Vec<f64> = (0..n).map(|i| 0.5 * (t[(i + 1).min(n - 1)] - t[i.saturating_sub(1)])).collect();
    let power = |f: f64| {
        let om = 2.0 * PI * f;
        let (mut re, mut im) = (0.0, 0.0);
        for i in 0..n {
            let (s, c) = (om * (t[i] - t[0])).sin_cos();
            re += w[i] * y[i] * c;
            im += w[i] * y[i] * s;
        }
        re * re + im * im
    };
    let k = 240;
    let step = 0.6 * f0 / f64::from(k);
    let freqs: Vec<f64> = (0..=k).map(|i| 0.7 * f0 + f64::from(i) * step).collect();
    let pw: Vec<f64> = freqs.iter().map(|&f| power(f)).collect();
    let best = (0..pw.len()).fold(0, |b, i| if pw[i] > pw[b] { i } else { b });
    if best == 0 || best == pw.len() - 1 {
        return freqs[best];
    }
    let (a, b, c) = (pw[best - 1], pw[best], pw[best + 1]);
    let den = a - 2.0 * b + c;
    let shift = if den < 0.0 { 0.5 * (a - c) / den } else { 0.0 };
    freqs[best] + shift.clamp(-1.0, 1.0) * step
}

/// σ (1/s) from the log decrement: minus the slope of ln(amplitude) of each cycle against its
/// middle time, over the cycles well above the noise (amplitude > 10 noise sd).
fn log_decrement(t: &[f64], y: &[f64], crossings: &[f64], omega: f64, noise: f64) -> Option<f64> {
    // Windows of whole cycles with at least 16 samples each (several cycles when sampled
    // sparsely).
    let per_cycle = t.len() as f64 / crossings.len().max(2) as f64;
    let stride = ((16.0 / per_cycle).ceil() as usize).max(1);
    let pts: Vec<(f64, f64)> = crossings
        .iter()
        .step_by(stride)
        .zip(crossings.iter().step_by(stride).skip(1))
        .filter_map(|(&a, &b)| {
            let amp = window_amplitude(t, y, a, b, omega)?;
            (amp > 10.0 * noise && amp > 0.0).then(|| (0.5 * (a + b), amp.ln()))
        })
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let (tt, ll): (Vec<f64>, Vec<f64>) = pts.into_iter().unzip();
    Some(-super::line(&tt, &ll).1)
}

/// Fits the structure's free decay in `s` with main mass `main_mass_kg` (kg). Errors name
/// `data` (too short, no decay) or `main-mass`.
// Over 80 lines: one Levenberg–Marquardt fit, from its start through its uncertainties, in order.
pub fn fit(s: &Series, main_mass_kg: f64) -> Result<StructureFit, ThudError> {
    crate::limits::MAIN_MASS.check(main_mass_kg)?;
    let l = look(s)?;
    let (t, y) = (s.t_s(), s.values());
    let f_start = spectrum_peak(t, &l.detrended, l.freq_hz);
    let omega = 2.0 * PI * f_start;
    // The log decrement; where it finds no decay, a small start (ζ 0.1 %) for the fit to refine
    // (which refuses the record if the decay stays unresolved).
    let sigma0 =
        log_decrement(t, &l.detrended, &l.crossings, omega, l.noise).filter(|&s| s > 0.0).unwrap_or(1e-3 * omega);
    // Normalised problem.
    let t0 = t[0];
    let span = s.span_s();
    let u: Vec<f64> = t.iter().map(|&ti| (ti - t0) / span).collect();
    let rms = (y.iter().map(|v| v * v).sum::<f64>() / y.len() as f64).sqrt();
    let scale = if rms > 0.0 { rms } else { 1.0 };
    let yn: Vec<f64> = y.iter().map(|v| v / scale).collect();
    // Linear start for A, B, o, d at the start's σ and ω_d.
    let (st, om) = (sigma0 * span, omega * span);
    let basis = DMatrix::from_fn(u.len(), 4, |i, k| {
        let e = (-st * u[i]).exp();
        match k {
            0 => e * (om * u[i]).cos(),
            1 => e * (om * u[i]).sin(),
            2 => 1.0,
            _ => u[i],
        }
    });
    let lin = basis
        .clone()
        .svd(true, true)
        .solve(&DVector::from_vec(yn.clone()), 1e-12)
        .map_err(|e| bad(format!("the start of the fit failed: {e}")))?;
    let problem = Problem { u, y: yn, p: OVector::<f64, U6>::from([st, om, lin[0], lin[1], lin[2], lin[3]]) };
    let (problem, report) = LevenbergMarquardt::new().with_patience(200).minimize(problem);
    let converged = report.termination.was_successful()
        || matches!(report.termination, TerminationReason::NoImprovementPossible(_));
    let p = problem.p;
    let r = problem.residuals().unwrap_or_else(|| DVector::zeros(0));
    let n = r.len();
    let rss = r.norm_squared();
    let dof = n.saturating_sub(6).max(1) as f64;
    let s2 = rss / dof;
    let cov = problem.jacobian().and_then(|j| (j.transpose() * j).try_inverse()).map(|m| m * s2).ok_or_else(|| {
        bad("the data do not determine the decay (the fit's Jacobian is singular); record more cycles")
    })?;
    let sigma = p[0] / span;
    let omega_d = p[1] / span;
    let var_sigma = cov[(0, 0)] / (span * span);
    let var_omega = cov[(1, 1)] / (span * span);
    let cov_so = cov[(0, 1)] / (span * span);
    let wn2 = omega_d * omega_d + sigma * sigma;
    let wn = wn2.sqrt();
    // Delta method: var(g) = ∇gᵀ Σ ∇g over (σ, ω_d).
    let sd = |gs: f64, gw: f64| (gs * gs * var_sigma + gw * gw * var_omega + 2.0 * gs * gw * cov_so).max(0.0).sqrt();
    let m = main_mass_kg;
    let fit = StructureFit {
        f_n_hz: wn / (2.0 * PI),
        f_n_hz_stderr: sd(sigma / wn, omega_d / wn) / (2.0 * PI),
        zeta: sigma / wn,
        zeta_stderr: sd(omega_d * omega_d / (wn2 * wn), -sigma * omega_d / (wn2 * wn)),
        k_n_m: m * wn2,
        k_n_m_stderr: sd(2.0 * m * sigma, 2.0 * m * omega_d),
        c_n_s_m: 2.0 * m * sigma,
        c_n_s_m_stderr: sd(2.0 * m, 0.0),
        main_mass_kg: m,
        residual_rms: (rss / n.max(1) as f64).sqrt() * scale,
        unit: s.quantity().unit().to_string(),
        converged,
        termination: format!("{:?}", report.termination),
        samples: s.len(),
        cycles: l.cycles,
        start_f_hz: f_start,
        start_zeta: sigma0 / omega.hypot(sigma0),
        model: DecayModel {
            t0_s: t0,
            sigma_1_s: sigma,
            omega_d_rad_s: omega_d,
            a: p[2] * scale,
            b: p[3] * scale,
            offset: p[4] * scale,
            drift_per_s: p[5] * scale / span,
        },
    };
    // No decay: the amplitude falls by less than 1 % over the record, or its decay rate is
    // not two standard errors above zero.
    if fit.converged && (sigma * span < 0.01 || sigma < 2.0 * var_sigma.max(0.0).sqrt()) {
        return Err(bad(format!(
            "no decay: the amplitude falls by {} % over the record; a fit needs a free decay after one strike",
            crate::units::sig(100.0 * (1.0 - (-sigma * span).exp()), 2)
        )));
    }
    // Standard errors the numbers cannot give (a residual of exactly 0, a covariance that
    // is not finite) are refused rather than printed as "± 0".
    let errors = [fit.f_n_hz_stderr, fit.zeta_stderr, fit.k_n_m_stderr, fit.c_n_s_m_stderr];
    if rss == 0.0 || errors.iter().any(|e| !e.is_finite() || *e <= 0.0) {
        return Err(bad(format!(
            "the record gives no standard errors (the fit's residual rms is {} {}); a fit needs a record with its noise",
            crate::units::short(fit.residual_rms),
            fit.unit
        )));
    }
    Ok(fit)
}

/// The main mass's velocity (m/s) at the record's start by the fitted model `m` of a signal of
/// kind `quantity`: the strike's speed when the record starts at the strike. The model is
/// Re(X·e^{λτ}) with X = A − iB and λ = −σ + iω_d, plus the offset and drift (which are the
/// sensor's, not the motion's): a displacement's velocity is Re(λX), a velocity's is A, an
/// acceleration's is Re(X/λ).
#[must_use]
pub fn start_velocity_m_s(m: &DecayModel, quantity: Quantity) -> f64 {
    let (sigma, wd, a, b) = (m.sigma_1_s, m.omega_d_rad_s, m.a, m.b);
    match quantity {
        Quantity::Displacement => -sigma * a + wd * b,
        Quantity::Velocity => a,
        Quantity::Acceleration => (-sigma * a - wd * b) / (sigma * sigma + wd * wd),
    }
}

/// The signal a structure with main mass M, stiffness K and damping C makes after a strike
/// that gives the main mass velocity `v0` at rest (x(0) = 0, x'(0) = v0), as `quantity`: the
/// closed form of Eq 25 (underdamped), for tests and examples.
#[must_use]
pub fn free_decay(main_mass_kg: f64, k_n_m: f64, c_n_s_m: f64, v0_m_s: f64, quantity: Quantity, t_s: f64) -> f64 {
    let sigma = c_n_s_m / (2.0 * main_mass_kg);
    let wd = (k_n_m / main_mass_kg - sigma * sigma).sqrt();
    let e = (-sigma * t_s).exp();
    let (s, c) = (wd * t_s).sin_cos();
    let x = v0_m_s / wd * e * s;
    let v = v0_m_s * e * (c - sigma / wd * s);
    match quantity {
        Quantity::Displacement => x,
        Quantity::Velocity => v,
        Quantity::Acceleration => -(k_n_m * x + c_n_s_m * v) / main_mass_kg,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::damper::{self, DamperParams, RunOptions, Solver};

    /// The repeatable generator of test noise.
    pub(crate) use crate::draws::SplitMix64 as Noise;

    /// Uneven times: a mean rate `rate_hz` with each step jittered ±40 %.
    pub(crate) fn uneven_times(span_s: f64, rate_hz: f64, g: &mut Noise) -> Vec<f64> {
        let mut t = vec![0.0];
        while t[t.len() - 1] < span_s {
            let last = t[t.len() - 1];
            t.push(last + (0.6 + 0.8 * g.uniform()) / rate_hz);
        }
        t
    }

    /// `clean` with white noise of `noise_frac` of its largest value, an offset and a drift.
    pub(crate) fn measured(t: &[f64], clean: &[f64], noise_frac: f64, g: &mut Noise) -> Vec<f64> {
        let peak = clean.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        t.iter()
            .zip(clean)
            .map(|(&ti, &c)| c + noise_frac * peak * g.normal() + 0.07 * peak + 0.02 * peak * ti)
            .collect()
    }

    fn check_within(fit: &StructureFit, f_n: f64, zeta: f64, m: f64) {
        let k = m * (2.0 * PI * f_n).powi(2);
        let c = 2.0 * zeta * m * 2.0 * PI * f_n;
        assert!(fit.converged, "{fit:?}");
        for (name, got, se, want) in [
            ("f_n", fit.f_n_hz, fit.f_n_hz_stderr, f_n),
            ("zeta", fit.zeta, fit.zeta_stderr, zeta),
            ("K", fit.k_n_m, fit.k_n_m_stderr, k),
            ("C", fit.c_n_s_m, fit.c_n_s_m_stderr, c),
        ] {
            assert!(se > 0.0 && se < 0.2 * want, "{name}: stderr {se} of {want}");
            assert!((got - want).abs() <= 3.0 * se, "{name}: {got} ± {se}, truth {want}");
        }
        // The acceptance: f_n within 0.5 %, ζ within 10 %.
        assert!((fit.f_n_hz / f_n - 1.0).abs() < 0.005 && (fit.zeta / zeta - 1.0).abs() < 0.1);
    }

    /// Closed-form decays (independent of thud's solvers) in x, v and a with 1–2 % noise, an
    /// offset, a drift and uneven sampling: every parameter inside 3 standard errors.
    #[test]
    fn closed_form_decays_are_recovered_within_three_standard_errors() {
        let mut g = Noise(23);
        for (q, m, k, c, rate, noise) in [
            (Quantity::Displacement, 0.5f64, 500.0f64, 0.3, 2000.0, 0.01),
            (Quantity::Velocity, 2.0, 8.0e4, 6.0, 5000.0, 0.02),
            (Quantity::Acceleration, 10.0, 3.0e6, 150.0, 10_000.0, 0.015),
        ] {
            let wn = (k / m).sqrt();
            let (f_n, zeta) = (wn / (2.0 * PI), c / (2.0 * m * wn));
            let span = 12.0 / f_n;
            let t = uneven_times(span, rate, &mut g);
            let clean: Vec<f64> = t.iter().map(|&ti| free_decay(m, k, c, 0.3, q, ti)).collect();
            let y = measured(&t, &clean, noise, &mut g);
            let s = Series::new(t, y, q).unwrap();
            let fit = fit(&s, m).unwrap();
            check_within(&fit, f_n, zeta, m);
            assert_eq!(fit.unit, q.unit());
        }
    }

    /// The strike's speed from the fitted model of each kind of record (closed-form decays,
    /// 1 % noise, offset and drift): within 1 % of the truth.
    #[test]
    fn the_start_velocity_is_read_from_each_kind_of_record() {
        let mut g = Noise(5);
        let (m, k, c, v0) = (2.0f64, 8.0e4f64, 6.0f64, 0.3f64);
        for q in [Quantity::Displacement, Quantity::Velocity, Quantity::Acceleration] {
            let t = uneven_times(1.5, 4000.0, &mut g);
            let clean: Vec<f64> = t.iter().map(|&ti| free_decay(m, k, c, v0, q, ti)).collect();
            let y = measured(&t, &clean, 0.01, &mut g);
            let f = fit(&Series::new(t, y, q).unwrap(), m).unwrap();
            let got = start_velocity_m_s(&f.model, q);
            assert!((got / v0 - 1.0).abs() < 0.01, "{q:?}: {got}");
        }
    }

    /// A sparsely sampled decay (about 5 samples a cycle: 400 Hz at 2 kHz) is still found: the
    /// log decrement then takes several cycles a window.
    #[test]
    fn a_sparsely_sampled_decay_is_recovered() {
        let mut g = Noise(11);
        let (m, f_n, zeta) = (1.0f64, 400.0f64, 0.002f64);
        let wn = 2.0 * PI * f_n;
        let (k, c) = (m * wn * wn, 2.0 * zeta * m * wn);
        let t = uneven_times(60.0 / f_n, 2000.0, &mut g);
        let clean: Vec<f64> = t.iter().map(|&ti| free_decay(m, k, c, 0.3, Quantity::Velocity, ti)).collect();
        let y = measured(&t, &clean, 0.01, &mut g);
        let fit = fit(&Series::new(t, y, Quantity::Velocity).unwrap(), m).unwrap();
        check_within(&fit, f_n, zeta, m);
    }

    /// The engine's own decay (the damper's solver with a clearance the ball never reaches).
    #[test]
    fn the_engines_decay_is_recovered() {
        let mut g = Noise(7);
        let p = DamperParams { damping_n_s_m: 0.8, gap_m: 5.0, v0_m_s: 0.2, duration_s: 3.0, ..DamperParams::table2() };
        let run = damper::simulate(&p, Solver::Event, &RunOptions { history_samples: 9000, cancel: None }).unwrap();
        assert!(run.impacts.is_empty());
        let t: Vec<f64> = run.history.iter().map(|h| h.t_s).collect();
        let x: Vec<f64> = run.history.iter().map(|h| h.x_m).collect();
        // Keep every sample with probability 2/3: uneven.
        let (t, x): (Vec<f64>, Vec<f64>) = t.into_iter().zip(x).filter(|_| g.uniform() < 0.67).unzip();
        let y = measured(&t, &x, 0.02, &mut g);
        let fit = fit(&Series::new(t, y, Quantity::Displacement).unwrap(), p.main_mass_kg).unwrap();
        let wn = (p.stiffness_n_m / p.main_mass_kg).sqrt();
        check_within(&fit, wn / (2.0 * PI), p.damping_n_s_m / (2.0 * p.main_mass_kg * wn), p.main_mass_kg);
    }

    #[test]
    fn no_decay_and_too_few_cycles_are_refused() {
        let t: Vec<f64> = (0..2000).map(|i| f64::from(i) * 1e-3).collect();
        let steady: Vec<f64> = t.iter().map(|&ti| (2.0 * PI * 5.0 * ti).sin()).collect();
        let e = fit(&Series::new(t.clone(), steady, Quantity::Displacement).unwrap(), 1.0).unwrap_err();
        assert!(e.to_string().contains("no decay"), "{e}");
        let short: Vec<f64> = t.iter().map(|&ti| (2.0 * PI * 1.0 * ti).sin() * (-0.1 * ti).exp()).collect();
        let e = fit(&Series::new(t, short, Quantity::Displacement).unwrap(), 1.0).unwrap_err();
        assert!(e.to_string().contains("too short"), "{e}");
    }
}
