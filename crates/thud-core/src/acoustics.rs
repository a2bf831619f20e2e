//! Sound radiated by a sphere under a Hertzian acceleration pulse (paper Eqs 9–24).
//!
//! Pressures in Pa, times in s, distances in m, angles in radians inside (degrees only in the
//! serialized form and at the user-facing edges). The model: docs/model.md §3–5.

use serde::{Deserialize, Serialize};

use crate::contact::Contact;
use crate::error::{check_positive, ThudError};

/// Reference pressure for levels, 20 µPa.
pub const P_REF_PA: f64 = 20e-6;

/// The air the sound travels through.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Air {
    /// Characteristic impedance ρ0·c (Pa·s/m). The paper's numbers need 400.
    pub rho_c_pa_s_m: f64,
    /// Speed of sound c (m/s).
    pub c_m_s: f64,
}

impl Default for Air {
    /// The paper's air: ρ0·c = 400 Pa·s/m, c = 343 m/s (standard air, 1.21 kg/m³, is +0.32 dB).
    fn default() -> Self {
        Self { rho_c_pa_s_m: 400.0, c_m_s: 343.0 }
    }
}

/// The specific gas constant of dry air R/M (J/(kg·K)), as ISO 2533:1975 (the standard
/// atmosphere) fixes it: the molar gas constant over dry air's molar mass 0.028 964 4 kg/mol.
/// docs/model.md §10.
pub const R_DRY_AIR_J_KG_K: f64 = 287.052_87;
/// The ratio of specific heats γ = c_p/c_v of dry air near room temperature (dimensionless;
/// ISO 2533:1975; a diatomic ideal gas, 7/5). docs/model.md §10.
pub const GAMMA_AIR: f64 = 1.4;
/// 0 °C in kelvin (the Celsius scale's zero, by definition of the SI).
pub const ZERO_CELSIUS_K: f64 = 273.15;
/// Standard room air for the physical model: 20 °C (ISO 554's standard atmosphere for testing)
/// and the standard sea-level pressure 101 325 Pa (ISO 2533:1975).
pub const ROOM_TEMPERATURE_C: f64 = 20.0;
/// The standard sea-level pressure (Pa), ISO 2533:1975.
pub const STANDARD_PRESSURE_PA: f64 = 101_325.0;

impl Air {
    /// Dry air as an ideal gas at `temperature_c` (°C) and `pressure_pa` (Pa), docs/model.md §10:
    /// ρ0 = p/(R·T), c = √(γ·R·T), so ρ0·c = p·√(γ/(R·T)), with R = [`R_DRY_AIR_J_KG_K`],
    /// γ = [`GAMMA_AIR`] and T = `temperature_c` + 273.15 K. At 20 °C and 101.325 kPa:
    /// ρ0 = 1.2041 kg/m³, c = 343.23 m/s, ρ0·c = 413.29 Pa·s/m.
    #[must_use]
    pub fn from_state(temperature_c: f64, pressure_pa: f64) -> Self {
        let t_k = temperature_c + ZERO_CELSIUS_K;
        let rho = pressure_pa / (R_DRY_AIR_J_KG_K * t_k);
        let c = (GAMMA_AIR * R_DRY_AIR_J_KG_K * t_k).sqrt();
        Self { rho_c_pa_s_m: rho * c, c_m_s: c }
    }

    pub fn validate(&self) -> Result<(), ThudError> {
        check_positive("rho-c", self.rho_c_pa_s_m, "Pa·s/m")?;
        check_positive("c", self.c_m_s, "m/s")
    }
}

/// Which reflecting surfaces surround the impact (method of images, Eqs 20–23).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// A free sphere: one source at the centre.
    Single,
    /// A sphere on a reflecting plane (Eq 20): source and its image.
    Dipole,
    /// A sphere in a wall–floor corner (Eq 22): source and three images.
    #[default]
    Quadrupole,
}

impl Source {
    pub const ALL: [Source; 3] = [Source::Single, Source::Dipole, Source::Quadrupole];

    pub fn name(self) -> &'static str {
        match self {
            Source::Single => "single",
            Source::Dipole => "dipole",
            Source::Quadrupole => "quadrupole",
        }
    }

    /// The valid observer angles θ (deg, lowest and highest): the open side of the source's
    /// reflecting surfaces (Eqs 20–23) — all round for a free sphere, the half-space above the
    /// plate for the dipole, the quarter-space of the wall–floor corner for the quadrupole.
    #[must_use]
    pub fn theta_range_deg(self) -> (f64, f64) {
        match self {
            Source::Single => (-180.0, 180.0),
            Source::Dipole => (-90.0, 90.0),
            Source::Quadrupole => (0.0, 90.0),
        }
    }
}

/// Signs of the two wall images of the quadrupole (Eq 22).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum QuadSigns {
    /// The paper's p1 − p2 + p3 − p4: a pressure-release second wall. Reproduces the paper.
    Paper,
    /// p1 − p2 − p3 + p4: a rigid second wall, as in a real enclosure corner (the default).
    #[default]
    Rigid,
}

impl QuadSigns {
    pub fn name(self) -> &'static str {
        match self {
            QuadSigns::Paper => "paper",
            QuadSigns::Rigid => "rigid",
        }
    }
}

/// Serde helper: an angle held in radians, written and read in degrees (`theta_deg`).
pub mod degrees {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(rad: &f64, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f64(rad.to_degrees())
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        f64::deserialize(d).map(f64::to_radians)
    }
}

/// Where the sound is heard: distance `r_m` from the contact point and polar angle `theta_rad`
/// from the plate's normal through the sphere's centre (docs/model.md §4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Observer {
    pub r_m: f64,
    #[serde(rename = "theta_deg", with = "degrees")]
    pub theta_rad: f64,
}

impl Observer {
    pub fn new(r_m: f64, theta_deg: f64) -> Self {
        Self { r_m, theta_rad: theta_deg.to_radians() }
    }
}

/// How the radiation is set up: source type, quadrupole signs and air.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Radiation {
    pub source: Source,
    pub quad_signs: QuadSigns,
    pub air: Air,
    /// The acceleration pulse: the paper's half-sine (default) or the exact Hertz pulse.
    #[serde(default)]
    pub pulse: PulseShape,
}

/// Response of the pressure to a unit impulse of acceleration, Eq 15 (Pa per m/s):
/// h(t') = ρ0c·(a/r)·cosθ·[cos λt' − (1 − a/r)·sin λt']·e^(−λt'), zero for t' < 0.
pub fn impulse_response(t_ret: f64, r: f64, cos_theta: f64, a: f64, air: &Air) -> f64 {
    if t_ret < 0.0 {
        return 0.0;
    }
    let lambda = air.c_m_s / a;
    let q = 1.0 - a / r;
    let lt = lambda * t_ret;
    air.rho_c_pa_s_m * (a / r) * cos_theta * (lt.cos() - q * lt.sin()) * (-lt).exp()
}

/// The shape of the sphere's acceleration during the contact.
/// Written as the `--pulse` flag spells it (`"half-sine"`, `"hertz"`); read also as `"half_sine"`
/// (thud 0.1's spelling).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PulseShape {
    /// The paper's half-sine, Eq 7 (its impulse is 2.342·U0 instead of 2·U0: +17 %).
    #[default]
    #[serde(alias = "half_sine")]
    HalfSine,
    /// The exact Hertz pulse A = (K_HZ/m)·α^1.5 with α'' = −K*·K_HZ·α^1.5 (impulse exactly
    /// 2·U0·M/(m+M) for an elastic rebound), as a sine series of odd harmonics of π/τ.
    Hertz,
}

impl PulseShape {
    pub fn name(self) -> &'static str {
        match self {
            PulseShape::HalfSine => "half-sine",
            PulseShape::Hertz => "hertz",
        }
    }

    /// Coefficients b_k of A(t)/A_max = Σ b_k·sin(kπt/τ) over odd k = 1, 3, 5, …
    pub fn sine_series(self) -> &'static [f64] {
        match self {
            PulseShape::HalfSine => &[1.0],
            PulseShape::Hertz => hertz_sine_series(),
        }
    }
}

/// The universal exact Hertz approach g(s) = α(sτ)/α_max on s ∈ [0, 1]: g'' = −(5/4)κ²·g^1.5,
/// g(0) = 0, g'(0) = κ (Eq 3 in units of α_max and τ). Returned at `n + 1` uniform points.
pub fn hertz_approach_shape(n: usize) -> Vec<f64> {
    let kappa = crate::contact::kappa();
    let c = 1.25 * kappa * kappa;
    let acc = |g: f64| -c * g.max(0.0).powf(1.5);
    let h = 1.0 / n as f64;
    let (mut g, mut v) = (0.0_f64, kappa);
    let mut out = Vec::with_capacity(n + 1);
    out.push(g);
    for _ in 0..n {
        // Classical RK4 on (g, g').
        let (k1g, k1v) = (v, acc(g));
        let (k2g, k2v) = (v + 0.5 * h * k1v, acc(g + 0.5 * h * k1g));
        let (k3g, k3v) = (v + 0.5 * h * k2v, acc(g + 0.5 * h * k2g));
        let (k4g, k4v) = (v + h * k3v, acc(g + h * k3g));
        g += h / 6.0 * (k1g + 2.0 * k2g + 2.0 * k3g + k4g);
        v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        out.push(g.max(0.0));
    }
    out
}

/// Sine-series coefficients of the exact Hertz acceleration g(s)^1.5 (odd k = 1 … 39), computed
/// once. The series converges like k^(−2.5) (the pulse starts as s^1.5).
fn hertz_sine_series() -> &'static [f64] {
    static SERIES: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    SERIES.get_or_init(|| {
        let n = 20_000;
        let a: Vec<f64> = hertz_approach_shape(n).into_iter().map(|g| g.powf(1.5)).collect();
        (0..20)
            .map(|j| {
                let k = f64::from(2 * j + 1);
                // Trapezoid rule; both ends vanish.
                let sum: f64 = (1..n).map(|i| a[i] * (k * std::f64::consts::PI * i as f64 / n as f64).sin()).sum();
                2.0 * sum / n as f64
            })
            .collect()
    })
}

/// One source's share of the closed-form pressure.
#[derive(Debug, Clone, Copy)]
struct SourceTerm {
    /// ±ρ0c·a·cosθ/(2r)·A_max (Pa·s⁴, before the 1/C2 of each harmonic).
    p_scale: f64,
    /// q = 1 − a/r.
    q: f64,
}

/// The constants C2…C6 and rates of one sine pulse sin(wt) on [0, τ], shared by all sources.
/// Eq 18 holds for 0 ≤ t' ≤ τ and the corrected Eq 19, p = P·{T(t') + T(t' − τ)}, after it
/// (for every odd harmonic w = kπ/τ, since then sin(w(ξ)) = −sin(w(ξ − τ))).
#[derive(Debug, Clone, Copy)]
struct PulseConstants {
    lambda: f64,
    w: f64,
    tau: f64,
    c2: f64,
    c3: f64,
    c4: f64,
    c5: f64,
    c6: f64,
}

impl PulseConstants {
    /// Constants of the harmonic w = kπ/τ (k odd).
    fn new(a: f64, tau: f64, k: f64, air: &Air) -> Self {
        let lambda = air.c_m_s / a;
        let w = k * std::f64::consts::PI / tau;
        let (l2, w2) = (lambda * lambda, w * w);
        Self {
            lambda,
            w,
            tau,
            c2: 4.0 * l2 * l2 + w2 * w2,
            c3: 4.0 * l2 * lambda + 2.0 * w2 * lambda,
            c4: 4.0 * l2 * lambda - 2.0 * w2 * lambda,
            c5: 2.0 * w2 * w,
            c6: 4.0 * w * l2,
        }
    }

    /// The decaying tail T(s) of docs/model.md §3.
    fn tail(&self, s: f64, q: f64) -> f64 {
        let (sn, cs) = (self.lambda * s).sin_cos();
        ((self.c5 * cs - self.c6 * sn) - q * (self.c6 * cs + self.c5 * sn)) * (-self.lambda * s).exp()
    }

    /// Pressure of one source at retarded time `t_ret`, divided by its `p_scale`.
    fn shape(&self, t_ret: f64, q: f64) -> f64 {
        if t_ret < 0.0 {
            0.0
        } else if t_ret <= self.tau {
            let (sn, cs) = (self.w * t_ret).sin_cos();
            self.c3 * sn - self.c5 * cs - q * (self.c4 * sn - self.c6 * cs) + self.tail(t_ret, q)
        } else {
            self.tail(t_ret, q) + self.tail(t_ret - self.tau, q)
        }
    }
}

/// One source of the image system: its sign, distance (m) and direction cosine, and its
/// retarded-time offset (r_i − a)/c (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageSource {
    pub sign: f64,
    pub r_m: f64,
    pub cos_theta: f64,
    pub delay_s: f64,
}

/// The image sources for `observer` around a sphere of radius `a` (m), Eqs 20–23.
pub fn image_sources(a: f64, observer: &Observer, radiation: &Radiation) -> Vec<ImageSource> {
    let (r, (sin_t, cos_t)) = (observer.r_m, observer.theta_rad.sin_cos());
    let c = radiation.air.c_m_s;
    let src =
        |sign: f64, r_i: f64, cos_i: f64| ImageSource { sign, r_m: r_i, cos_theta: cos_i, delay_s: (r_i - a) / c };
    let r1 = (r * r + a * a - 2.0 * a * r * cos_t).sqrt();
    let s1 = src(1.0, r1, (r * cos_t - a) / r1);
    if radiation.source == Source::Single {
        return vec![s1];
    }
    let r2 = (r * r + a * a + 2.0 * a * r * cos_t).sqrt();
    let s2 = src(-1.0, r2, (r * cos_t + a) / r2);
    if radiation.source == Source::Dipole {
        return vec![s1, s2];
    }
    // Quadrupole: sinθ_i = r·sinθ/r_i, so 4a·r_i·sinθ_i = 4a·r·sinθ.
    let r3 = (r2 * r2 + 4.0 * a * a + 4.0 * a * r * sin_t).sqrt();
    let r4 = (r1 * r1 + 4.0 * a * a + 4.0 * a * r * sin_t).sqrt();
    let wall_sign = match radiation.quad_signs {
        QuadSigns::Paper => 1.0,
        QuadSigns::Rigid => -1.0,
    };
    vec![s1, s2, src(wall_sign, r3, (r * cos_t + a) / r3), src(-wall_sign, r4, (r * cos_t - a) / r4)]
}

/// Checks that the observer is a valid field point for this radiation: outside the sphere,
/// on the open side of the plate (and of the second wall for the quadrupole).
pub fn validate_observer(a: f64, observer: &Observer, source: Source) -> Result<(), ThudError> {
    let (r, theta) = (observer.r_m, observer.theta_rad);
    check_positive("r", r, "m")?;
    if !theta.is_finite() {
        return Err(ThudError::invalid("theta", "not a number; must be an angle in degrees"));
    }
    let r1 = (r * r + a * a - 2.0 * a * r * theta.cos()).sqrt();
    if r <= a || r1 <= a {
        // Outside the sphere (centre a along the normal) at θ: r > 2a·cos θ; and r > a.
        let far = 2.0 * a * theta.cos();
        let bound = if far > a {
            format!(
                "at θ {} deg it must be > 2a·cos θ = {} m (a = {} m, the sphere's radius)",
                crate::units::short(theta.to_degrees()),
                crate::units::short(far),
                crate::units::short(a)
            )
        } else {
            format!("must be > the sphere's radius {} m", crate::units::short(a))
        };
        return Err(ThudError::invalid("r", format!("{r} m puts the observer inside the sphere; {bound}")));
    }
    let deg = theta.to_degrees();
    let (lo, hi) = source.theta_range_deg();
    if !(lo - 1e-9..=hi + 1e-9).contains(&deg) {
        return Err(ThudError::invalid(
            "theta",
            format!(
                "{} deg is behind a reflecting wall of the {} source; must be between {lo} and {hi} deg",
                crate::units::sig(deg, 6),
                source.name()
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod observer_tests {
    use super::*;

    /// The error names the bound at the angle given: the sphere's far side 2a·cos θ along the
    /// normal, its radius where that is smaller; a point just past the bound is accepted.
    #[test]
    fn an_observer_inside_the_sphere_is_told_the_bound_at_its_angle() {
        let a = 0.01905;
        let at =
            |r_m: f64, deg: f64| validate_observer(a, &Observer { r_m, theta_rad: deg.to_radians() }, Source::Dipole);
        let e = at(0.037, 0.0).unwrap_err().to_string();
        assert!(e.contains("must be > 2a·cos θ = 0.0381 m"), "{e}");
        assert!(at(0.0382, 0.0).is_ok(), "just outside the sphere along the normal");
        let e = at(0.015, 80.0).unwrap_err().to_string();
        assert!(e.contains("must be > the sphere's radius 0.01905 m"), "{e}");
        let far = 2.0 * a * 30f64.to_radians().cos();
        assert!(at(0.999 * far, 30.0).is_err() && at(1.001 * far, 30.0).is_ok(), "the bound at 30°: {far}");
    }
}

/// Levels of one pressure pulse.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Levels {
    /// SPL from the rms pressure over one contact duration τ from the direct arrival (dB re 20 µPa).
    /// This is the paper's Table 1 convention.
    pub spl_db: f64,
    /// rms pressure over the same window (Pa).
    pub p_rms_pa: f64,
    /// Peak level 20·log10(max|p|/p_ref) (dB).
    pub spl_peak_db: f64,
    /// Sound exposure level 10·log10(∫p²dt / (p_ref²·1 s)) over the whole pulse (dB).
    pub sel_db: f64,
    /// Largest and smallest pressure (Pa).
    pub p_max_pa: f64,
    pub p_min_pa: f64,
}

/// A local extremum of the pressure waveform.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Extremum {
    pub t_s: f64,
    pub p_pa: f64,
}

/// The pressure field of one impact at one observer: everything needed to evaluate p(t).
/// Time `t` is measured from the start of the contact.
#[derive(Debug, Clone)]
pub struct Field {
    /// The fundamental (k = 1): τ, λ and the time scales.
    consts: PulseConstants,
    /// Each odd harmonic of the pulse with its weight b_k/C2_k.
    harmonics: Vec<(PulseConstants, f64)>,
    sources: Vec<(ImageSource, SourceTerm)>,
}

impl Field {
    /// Builds the field of a sphere of radius `radius_m` with contact `contact` heard at
    /// `observer`. Validates the geometry and the air.
    pub fn new(
        radius_m: f64,
        contact: &Contact,
        observer: &Observer,
        radiation: &Radiation,
    ) -> Result<Self, ThudError> {
        check_positive("radius", radius_m, "m")?;
        radiation.air.validate()?;
        validate_observer(radius_m, observer, radiation.source)?;
        if !(contact.tau_s.is_finite() && contact.tau_s > 0.0 && contact.accel_max_m_s2.is_finite()) {
            return Err(ThudError::invalid("u0", "the contact has no finite duration; U0 must be > 0"));
        }
        let air = radiation.air;
        let harmonics: Vec<(PulseConstants, f64)> = radiation
            .pulse
            .sine_series()
            .iter()
            .enumerate()
            .map(|(j, &b)| {
                let c = PulseConstants::new(radius_m, contact.tau_s, (2 * j + 1) as f64, &air);
                (c, b / c.c2)
            })
            .collect();
        let sources = image_sources(radius_m, observer, radiation)
            .into_iter()
            .map(|s| {
                let p_scale = air.rho_c_pa_s_m * radius_m * s.cos_theta / (2.0 * s.r_m) * contact.accel_max_m_s2;
                (s, SourceTerm { p_scale: s.sign * p_scale, q: 1.0 - radius_m / s.r_m })
            })
            .collect();
        Ok(Self { consts: harmonics[0].0, harmonics, sources })
    }

    /// Contact duration τ (s).
    pub fn tau_s(&self) -> f64 {
        self.consts.tau
    }

    /// Arrival time of the direct wave (s after the contact starts), (r1 − a)/c.
    pub fn arrival_s(&self) -> f64 {
        self.sources[0].0.delay_s
    }

    /// The image sources of this field.
    pub fn sources(&self) -> impl Iterator<Item = &ImageSource> {
        self.sources.iter().map(|(s, _)| s)
    }

    /// Time by which the last wave has decayed to ~e^(−30) of its size (s).
    pub fn end_s(&self) -> f64 {
        let last = self.sources().map(|s| s.delay_s).fold(0.0, f64::max);
        last + self.consts.tau + 30.0 / self.consts.lambda
    }

    /// Pressure (Pa) at time `t_s` after the contact starts: the sum over the image sources,
    /// each with its own retarded time (Eqs 20–23), of the closed form (Eq 18, corrected Eq 19).
    pub fn pressure(&self, t_s: f64) -> f64 {
        self.sources
            .iter()
            .map(|(s, term)| {
                let t_ret = t_s - s.delay_s;
                term.p_scale * self.harmonics.iter().map(|(c, weight)| weight * c.shape(t_ret, term.q)).sum::<f64>()
            })
            .sum()
    }

    /// Time points where p(t) has kinks (arrivals and ends of each source's forced part).
    fn breakpoints(&self) -> Vec<f64> {
        let mut b: Vec<f64> = self.sources().flat_map(|s| [s.delay_s, s.delay_s + self.consts.tau]).collect();
        b.sort_by(f64::total_cmp);
        b
    }

    /// ∫ f(p(t)) dt over [t0, t1] by Gauss–Legendre on the smooth pieces between kinks.
    fn integrate(&self, t0: f64, t1: f64, f: impl Fn(f64) -> f64) -> f64 {
        let mut cuts = vec![t0];
        cuts.extend(self.breakpoints().into_iter().filter(|&b| b > t0 && b < t1));
        cuts.push(t1);
        // The waveform varies on the scales 1/λ and τ/π: ten GL nodes per such scale suffice.
        let scale = self.scale_s();
        cuts.windows(2)
            .map(|w| {
                let n = ((w[1] - w[0]) / scale).ceil().clamp(1.0, 400.0) as usize;
                gauss_legendre(w[0], w[1], n, |t| f(self.pressure(t)))
            })
            .sum()
    }

    /// Mean square pressure (Pa²) over one contact duration from the direct arrival (Table 1).
    pub fn mean_square_over_tau(&self) -> f64 {
        let t0 = self.arrival_s();
        self.integrate(t0, t0 + self.consts.tau, |p| p * p) / self.consts.tau
    }

    /// The shortest time scale of the waveform (s): min(1/λ, τ/(kπ)), with k = 1 for the
    /// half-sine and k = 4 for the Hertz pulse (whose harmonics above the 7th are < 1 %).
    fn scale_s(&self) -> f64 {
        let k = if self.harmonics.len() > 1 { 4.0 } else { 1.0 };
        (1.0 / self.consts.lambda).min(self.consts.tau / (k * std::f64::consts::PI))
    }

    /// p(t) sampled over the pulse: the start, the step and the samples.
    fn sampled(&self) -> (f64, f64, Vec<f64>) {
        let last = self.sources().map(|s| s.delay_s).fold(0.0, f64::max);
        // After the last forced part the tail falls as e^(−λt): e^(−12) of the peak is nothing.
        let (t0, t1) = (self.arrival_s(), last + self.consts.tau + 12.0 / self.consts.lambda);
        let n = (((t1 - t0) / (0.1 * self.scale_s())).ceil() as usize).clamp(100, 20_000);
        let dt = (t1 - t0) / n as f64;
        (t0, dt, (0..=n).map(|i| self.pressure(t0 + i as f64 * dt)).collect())
    }

    /// The local extrema of the samples `p` (from `t0`, step `dt`) larger than `floor` (Pa),
    /// each refined to ~1e-13 s.
    fn refined(&self, t0: f64, dt: f64, p: &[f64], floor: f64) -> Vec<Extremum> {
        let mut out = Vec::new();
        for i in 1..p.len().saturating_sub(1) {
            let (a, b, c) = (p[i - 1], p[i], p[i + 1]);
            let is_max = b > a && b >= c;
            let is_min = b < a && b <= c;
            if (is_max || is_min) && b.abs() > floor {
                let sign = if is_max { 1.0 } else { -1.0 };
                let t = golden_max(t0 + (i - 1) as f64 * dt, t0 + (i + 1) as f64 * dt, |t| sign * self.pressure(t));
                out.push(Extremum { t_s: t, p_pa: self.pressure(t) });
            }
        }
        out
    }

    /// Local extrema of p(t) over the pulse, in time order, each refined to ~1e-13 s.
    pub fn extrema(&self) -> Vec<Extremum> {
        let (t0, dt, p) = self.sampled();
        let peak = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        self.refined(t0, dt, &p, 1e-6 * peak)
    }

    /// The peak level 20·log10(max|p|/20 µPa) (dB), as [`Field::levels`]' `spl_peak_db` to the
    /// last bit, refining only the extrema within 20 % of the largest sample (the samples are a
    /// tenth of the waveform's shortest time scale apart, so the largest extremum is among
    /// them): the physical model's level, cheap enough for every impact of a run.
    pub fn peak_db(&self) -> f64 {
        let (t0, dt, p) = self.sampled();
        let peak = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let ext = self.refined(t0, dt, &p, 0.8 * peak);
        let p_max = ext.iter().map(|e| e.p_pa).fold(0.0, f64::max);
        let p_min = ext.iter().map(|e| e.p_pa).fold(0.0, f64::min);
        20.0 * (p_max.max(-p_min) / P_REF_PA).log10()
    }

    /// The extrema larger than `fraction` of the largest |p|: the peaks a person would name.
    pub fn significant_extrema(&self, fraction: f64) -> Vec<Extremum> {
        let ext = self.extrema();
        let peak = ext.iter().fold(0.0_f64, |m, e| m.max(e.p_pa.abs()));
        ext.into_iter().filter(|e| e.p_pa.abs() > fraction * peak).collect()
    }

    /// The significant extrema as "+1.853 Pa at 0.0856 ms" (time after the direct arrival).
    pub fn describe_peaks(&self) -> String {
        let t0 = self.arrival_s();
        let items: Vec<String> = self
            .significant_extrema(0.02)
            .iter()
            .map(|e| format!("{:+.3} Pa at {:.4} ms", e.p_pa, (e.t_s - t0) * 1e3))
            .collect();
        items.join(", ")
    }

    /// All the levels of this pulse (see [`Levels`]).
    pub fn levels(&self) -> Levels {
        let ms = self.mean_square_over_tau();
        let exposure = self.integrate(self.arrival_s(), self.end_s(), |p| p * p);
        let ext = self.extrema();
        let p_max = ext.iter().map(|e| e.p_pa).fold(0.0, f64::max);
        let p_min = ext.iter().map(|e| e.p_pa).fold(0.0, f64::min);
        let p_abs = p_max.max(-p_min);
        Levels {
            spl_db: 10.0 * (ms / (P_REF_PA * P_REF_PA)).log10(),
            p_rms_pa: ms.sqrt(),
            spl_peak_db: 20.0 * (p_abs / P_REF_PA).log10(),
            sel_db: 10.0 * (exposure / (P_REF_PA * P_REF_PA)).log10(),
            p_max_pa: p_max,
            p_min_pa: p_min,
        }
    }

    /// SPL (dB) over τ from the direct arrival only: the cheap level used by sweeps.
    pub fn spl_db(&self) -> f64 {
        10.0 * (self.mean_square_over_tau() / (P_REF_PA * P_REF_PA)).log10()
    }

    /// The waveform sampled at `n` uniform times from slightly before the direct arrival to
    /// the decay of the last wave: (t in s after contact start, p in Pa).
    pub fn waveform(&self, n: usize) -> (Vec<f64>, Vec<f64>) {
        let last = self.sources().map(|s| s.delay_s).fold(0.0, f64::max);
        let t0 = self.arrival_s() - 0.1 * self.consts.tau;
        let t1 = last + 1.5 * self.consts.tau + 6.0 / self.consts.lambda;
        let n = n.max(2);
        let t: Vec<f64> = (0..n).map(|i| t0 + (t1 - t0) * i as f64 / (n - 1) as f64).collect();
        let p = t.iter().map(|&ti| self.pressure(ti)).collect();
        (t, p)
    }
}

/// Pressure of one source by direct numerical quadrature of the convolution, Eq 16, with the
/// half-sine pulse (used to check the closed form).
pub fn pressure_by_quadrature(t_ret: f64, r: f64, cos_theta: f64, a: f64, contact: &Contact, air: &Air) -> f64 {
    let upper = t_ret.min(contact.tau_s);
    if upper <= 0.0 {
        return 0.0;
    }
    let n = 200;
    gauss_legendre(0.0, upper, n, |xi| impulse_response(t_ret - xi, r, cos_theta, a, air) * contact.half_sine(xi))
}

/// Composite 10-point Gauss–Legendre rule of ∫f over [a, b] on `n` equal panels.
pub fn gauss_legendre(a: f64, b: f64, n: usize, f: impl Fn(f64) -> f64) -> f64 {
    const X: [f64; 5] = [
        0.148_874_338_981_631_2,
        0.433_395_394_129_247_2,
        0.679_409_568_299_024_4,
        0.865_063_366_688_984_5,
        0.973_906_528_517_171_7,
    ];
    const W: [f64; 5] = [
        0.295_524_224_714_752_9,
        0.269_266_719_309_996_4,
        0.219_086_362_515_982,
        0.149_451_349_150_580_6,
        0.066_671_344_308_688_1,
    ];
    let h = (b - a) / n as f64;
    let mut total = 0.0;
    for k in 0..n {
        let mid = a + (k as f64 + 0.5) * h;
        let half = 0.5 * h;
        let mut s = 0.0;
        for (x, w) in X.iter().zip(W) {
            s += w * (f(mid - half * x) + f(mid + half * x));
        }
        total += s * half;
    }
    total
}

/// Maximiser of a unimodal `f` on [a, b] by golden-section search (to ~1e-13 of the bracket).
fn golden_max(mut a: f64, mut b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..64 {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

/// SPL (dB, rms over τ) and rms pressure (Pa) against θ at fixed r (Figs 3 and 6).
pub fn directivity(
    radius_m: f64,
    contact: &Contact,
    r_m: f64,
    thetas_rad: &[f64],
    radiation: &Radiation,
) -> Result<Vec<(f64, Levels)>, ThudError> {
    thetas_rad
        .iter()
        .map(|&th| Field::new(radius_m, contact, &Observer { r_m, theta_rad: th }, radiation).map(|f| (th, f.levels())))
        .collect()
}

#[cfg(test)]
mod tests;
