//! What one design is worth: the zones, the damping inclination (Eq 27), peak contact speed,
//! peak SPL, the steady state's level and a run's truncation.

use std::sync::atomic::AtomicBool;

use serde::{Deserialize, Serialize};

use crate::acoustics::{gauss_legendre, Field, PulseShape, P_REF_PA};
use crate::damper::{self, Run, RunOptions, SteadyMotion};
use crate::error::ThudError;

use super::{Design, Thresholds, U0MaxRule, ValidDesign, ZoneBy};

/// Zones of the design chart (docs/model.md §6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Zone {
    /// 1: noisy and weak (SPL ≥ L*, e < e*).
    NoisyWeak = 1,
    /// 2: noisy and strong.
    NoisyStrong = 2,
    /// 3: quiet and strong — the target.
    QuietStrong = 3,
    /// 4: quiet and weak.
    QuietWeak = 4,
}

impl Zone {
    /// The zone's number 1–4: how every file (CSV, JSON) and Python write it.
    pub fn number(self) -> u8 {
        self as u8
    }

    /// The zone numbered `n` (1–4).
    #[must_use]
    pub fn from_number(n: u8) -> Option<Zone> {
        [Zone::NoisyWeak, Zone::NoisyStrong, Zone::QuietStrong, Zone::QuietWeak].into_iter().find(|z| z.number() == n)
    }

    pub fn describe(self) -> &'static str {
        match self {
            Zone::NoisyWeak => "noisy, weak",
            Zone::NoisyStrong => "noisy, strong",
            Zone::QuietStrong => "quiet, strong",
            Zone::QuietWeak => "quiet, weak",
        }
    }

    /// The zone of a design with peak SPL `spl_db` and inclination `e_cm_s`.
    pub fn classify(spl_db: f64, e_cm_s: f64, t: &Thresholds) -> Zone {
        match (spl_db >= t.spl_db, e_cm_s >= t.inclination_cm_s) {
            (true, false) => Zone::NoisyWeak,
            (true, true) => Zone::NoisyStrong,
            (false, true) => Zone::QuietStrong,
            (false, false) => Zone::QuietWeak,
        }
    }
}

/// What one design is worth (the default: a run with no impact and no motion).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    pub n_impacts: usize,
    /// Damping inclination e (Eq 27) from the first two cycle maxima (cm/s); None if < 2 maxima.
    pub inclination_cm_s: Option<f64>,
    /// −(least-squares slope of the maxima while X_k ≥ X1/2) (cm/s); None if < 2 such maxima.
    pub inclination_fit_cm_s: Option<f64>,
    /// Largest contact speed by the design's U0max rule (m/s).
    pub u0_max_m_s: f64,
    /// Largest |z'| over the whole run including t = 0 (m/s).
    pub zdot_abs_max_m_s: f64,
    /// SPL (dB) of an impact at U0max; None when there is no impact (and the rule is `impacts`).
    pub spl_max_db: Option<f64>,
    /// Duration (s) of the Hertz contact at U0max (closed form, K* = (m+M)/(mM)).
    pub contact_duration_s: Option<f64>,
    /// Mean restitution u_out/u_in over the impacts.
    pub restitution_mean: Option<f64>,
    /// The zone, when both e and SPLmax exist; written as its number 1–4.
    #[serde(with = "zone_number")]
    pub zone: Option<Zone>,
}

/// A zone written as its number 1–4 (never the enum's name): how `--json`, the CSV files and
/// Python write it. Serde `with` module for `Option<Zone>`.
pub mod zone_number {
    use super::Zone;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(z: &Option<Zone>, s: S) -> Result<S::Ok, S::Error> {
        z.map(Zone::number).serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Zone>, D::Error> {
        Option::<u8>::deserialize(d)?
            .map(|n| Zone::from_number(n).ok_or_else(|| serde::de::Error::custom(format!("zone {n}; must be 1 to 4"))))
            .transpose()
    }
}

impl Metrics {
    /// The inclination (cm/s) that `by` names: Eq 27's e or the robust e_fit; None if the run
    /// had too few maxima for it.
    #[must_use]
    pub fn inclination_by(&self, by: ZoneBy) -> Option<f64> {
        match by {
            ZoneBy::Paper => self.inclination_cm_s,
            ZoneBy::Fit => self.inclination_fit_cm_s,
        }
    }

    /// The zone (Figs 15–17) of these metrics under `t`, by the inclination `t` names; None
    /// without SPLmax or without that inclination. The stored [`Metrics::zone`] field is this
    /// under the thresholds the metrics were computed with.
    #[must_use]
    pub fn zone(&self, t: &Thresholds) -> Option<Zone> {
        Some(Zone::classify(self.spl_max_db?, self.inclination_by(t.zone_by)?, t))
    }
}

/// Damping inclination of Eq 27, e = (X1 − X2)/(t2 − t1), in cm/s.
pub fn inclination_cm_s(maxima: &[damper::Maximum]) -> Option<f64> {
    let (m1, m2) = (maxima.first()?, maxima.get(1)?);
    Some(100.0 * (m1.x_m - m2.x_m) / (m2.t_s - m1.t_s))
}

/// Robust inclination: minus the least-squares slope of X_k against t_k over the leading maxima
/// with X_k ≥ X1/2, in cm/s.
pub fn inclination_fit_cm_s(maxima: &[damper::Maximum]) -> Option<f64> {
    let x1 = maxima.first()?.x_m;
    let pts: Vec<&damper::Maximum> = maxima.iter().take_while(|m| m.x_m >= 0.5 * x1).collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (st, sx) = pts.iter().fold((0.0, 0.0), |(a, b), m| (a + m.t_s, b + m.x_m));
    let (mt, mx) = (st / n, sx / n);
    let (num, den) =
        pts.iter().fold((0.0, 0.0), |(a, b), m| (a + (m.t_s - mt) * (m.x_m - mx), b + (m.t_s - mt).powi(2)));
    Some(-100.0 * num / den)
}

/// The metrics of a finished run of `design`.
pub fn metrics(run: &Run, design: &ValidDesign) -> Result<Metrics, ThudError> {
    run_metrics(run, design)
}

/// [`metrics`] of a run of a design derived from a [`ValidDesign`] (resolved and valid).
pub(crate) fn run_metrics(run: &Run, design: &Design) -> Result<Metrics, ThudError> {
    let impact_max = run.impacts.iter().map(|i| i.u_in_m_s).fold(0.0, f64::max);
    let u0_max = match design.u0max_rule {
        U0MaxRule::Impacts => impact_max,
        U0MaxRule::WholeRun => run.zdot_abs_max_m_s,
    };
    let sounding = u0_max > 0.0 && (design.u0max_rule == U0MaxRule::WholeRun || !run.impacts.is_empty());
    let (spl_max_db, contact_duration_s) = if sounding {
        let f = design.impact_field(u0_max)?;
        (Some(design.level_db(&f)), Some(f.tau_s()))
    } else {
        (None, None)
    };
    let e = inclination_cm_s(&run.maxima);
    let e_fit = inclination_fit_cm_s(&run.maxima);
    let restitution_mean = (!run.impacts.is_empty())
        .then(|| run.impacts.iter().map(|i| i.u_out_m_s / i.u_in_m_s).sum::<f64>() / run.impacts.len() as f64);
    let mut m = Metrics {
        n_impacts: run.impacts.len(),
        inclination_cm_s: e,
        inclination_fit_cm_s: e_fit,
        u0_max_m_s: u0_max,
        zdot_abs_max_m_s: run.zdot_abs_max_m_s,
        spl_max_db,
        contact_duration_s,
        restitution_mean,
        zone: None,
    };
    m.zone = m.zone(&design.thresholds);
    Ok(m)
}

/// A design run through its solver, with its metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    pub run: Run,
    pub metrics: Metrics,
    /// The steady state of a forced design with the level of its rattle (absent without a
    /// force; a chart cell's [`Metrics`] do not carry it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steady: Option<Steady>,
}

/// Simulates `design` and computes its metrics. `history_samples` uniform samples of x and y
/// are kept for plotting (0 for none); `cancel` stops the run between impacts.
pub fn evaluate(
    design: &ValidDesign,
    history_samples: usize,
    cancel: Option<&AtomicBool>,
) -> Result<Evaluation, ThudError> {
    evaluate_checked(design, history_samples, cancel)
}

/// [`evaluate`] of a design the engine derived from a [`ValidDesign`] by a change that keeps
/// it valid and resolved (an ensemble run's ball offset inside the clearance, which no check
/// and not K_HZ depends on beyond |y0| < d/2).
pub(crate) fn evaluate_checked(
    d: &Design,
    history_samples: usize,
    cancel: Option<&AtomicBool>,
) -> Result<Evaluation, ThudError> {
    let run = damper::simulate(&d.damper, d.solver, &RunOptions { history_samples, cancel })?;
    let metrics = run_metrics(&run, d)?;
    let steady = run_steady(&run, d)?;
    Ok(Evaluation { run, metrics, steady })
}

/// The steady state of a forced run of a design: the motion over the last window
/// ([`SteadyMotion`], whose fields it reads as its own) and the level of the rattle over it.
///
/// Written (JSON, CSV, Python) as the window, amplitudes, impacts per period, `leq_db`, the
/// three flags and the verdict, in that order: without the motion's impact count and previous
/// amplitude, which a `Steady` read back from JSON holds as 0 and None.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
pub struct Steady {
    /// The motion over the last window.
    #[serde(flatten)]
    pub motion: SteadyMotion,
    /// Energy-average level at the observer over the window (dB re 20 µPa); None when no
    /// impact sounds in it.
    pub leq_db: Option<f64>,
}

impl std::ops::Deref for Steady {
    type Target = SteadyMotion;

    fn deref(&self) -> &SteadyMotion {
        &self.motion
    }
}

impl Serialize for Steady {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let m = &self.motion;
        let mut st = ser.serialize_struct("Steady", 12)?;
        st.serialize_field("periods", &m.periods)?;
        st.serialize_field("window_start_s", &m.window_start_s)?;
        st.serialize_field("window_end_s", &m.window_end_s)?;
        st.serialize_field("amplitude_m", &m.amplitude_m)?;
        st.serialize_field("amplitude_linear_m", &m.amplitude_linear_m)?;
        st.serialize_field("reduction_db", &m.reduction_db)?;
        st.serialize_field("impacts_per_period", &m.impacts_per_period)?;
        st.serialize_field("leq_db", &self.leq_db)?;
        st.serialize_field("periodic", &m.periodic)?;
        st.serialize_field("settled", &m.settled)?;
        st.serialize_field("truncated", &m.truncated)?;
        st.serialize_field("verdict", &m.verdict)?;
        st.end()
    }
}

/// The steady state of `run` of `design`, if the design is forced.
pub fn steady(run: &Run, design: &ValidDesign) -> Result<Option<Steady>, ThudError> {
    run_steady(run, design)
}

/// [`steady`] of a run of a design derived from a [`ValidDesign`] (resolved and valid: a
/// response's design at one frequency).
pub(crate) fn run_steady(run: &Run, design: &Design) -> Result<Option<Steady>, ThudError> {
    let Some(m) = run.steady else { return Ok(None) };
    Ok(Some(Steady { motion: m, leq_db: run_leq_db(run, design, m.window_start_s, m.window_end_s)? }))
}

/// `Leq` (dB re 20 µPa) of the impacts of `run` of `design` over `[a, b]` (s); None when no
/// pulse reaches the window.
pub fn leq_db(run: &Run, design: &ValidDesign, a: f64, b: f64) -> Result<Option<f64>, ThudError> {
    run_leq_db(run, design, a, b)
}

/// [`leq_db`] of a run of a design derived from a [`ValidDesign`] (resolved and valid).
fn run_leq_db(run: &Run, design: &Design, a: f64, b: f64) -> Result<Option<f64>, ThudError> {
    if b <= a {
        return Ok(None);
    }
    // Pulses last about a millisecond; build the fields of the impacts near the window only.
    // After the last source's forced part the pressure falls as e^(−λs), λ = c/a: 18/λ later
    // its square is e^(−36) (2e-16) of what it was, and the rest of the integral no more.
    let a_over_c = design.ball_radius_m() / design.sound().air.c_m_s;
    let mut pulses: Vec<(f64, f64, f64, Field)> = Vec::new();
    for i in run.impacts.iter().filter(|i| i.t_s <= b && i.t_s >= a - 1.0) {
        let f = design.impact_field(i.u_in_m_s)?;
        let last = f.sources().map(|s| s.delay_s).fold(0.0, f64::max);
        let (start, end) = (i.t_s + f.arrival_s(), i.t_s + last + f.tau_s() + 18.0 * a_over_c);
        if end > a && start < b {
            pulses.push((start, end, i.t_s, f));
        }
    }
    if pulses.is_empty() {
        return Ok(None);
    }
    pulses.sort_by(|p, q| p.0.total_cmp(&q.0));
    // The waveform's shortest time scale: a/c and τ/(kπ) (k = 4 for the Hertz pulse's harmonics).
    // Between kinks the pulse is smooth on that scale: a 10-point Gauss–Legendre panel five
    // scales long integrates it to rounding (its error bound there is below 1e-15).
    let k = if design.sound().pulse == PulseShape::Hertz { 4.0 } else { 1.0 };
    let mut exposure = 0.0;
    let mut i = 0;
    while i < pulses.len() {
        // A cluster of pulses whose supports overlap.
        let mut j = i + 1;
        let mut end = pulses[i].1;
        while j < pulses.len() && pulses[j].0 < end {
            end = end.max(pulses[j].1);
            j += 1;
        }
        let cluster = &pulses[i..j];
        let (lo, hi) = (cluster[0].0.max(a), end.min(b));
        let mut cuts = vec![lo, hi];
        let mut scale = a_over_c;
        for (_, _, t_i, f) in cluster {
            scale = scale.min(f.tau_s() / (k * std::f64::consts::PI));
            for s in f.sources() {
                cuts.extend([t_i + s.delay_s, t_i + s.delay_s + f.tau_s()].into_iter().filter(|&c| c > lo && c < hi));
            }
        }
        cuts.sort_by(f64::total_cmp);
        let p = |t: f64| cluster.iter().map(|(_, _, t_i, f)| f.pressure(t - t_i)).sum::<f64>();
        for w in cuts.windows(2) {
            let n = ((w[1] - w[0]) / (5.0 * scale)).ceil().clamp(1.0, 400.0) as usize;
            exposure += gauss_legendre(w[0], w[1], n, |t| {
                let v = p(t);
                v * v
            });
        }
        i = j;
    }
    if exposure <= 0.0 {
        return Ok(None);
    }
    Ok(Some(10.0 * (exposure / ((b - a) * P_REF_PA * P_REF_PA)).log10()))
}

/// Why `run` stopped before the design's duration `duration_s`, if it did: the engine's own
/// [`Run::truncated`] (which solver cap was reached) with the time reached.
pub fn truncation(run: &Run, duration_s: f64) -> Option<String> {
    run.truncated.map(|why| {
        format!(
            "{} at t = {} s of {} s; the results cover only that time",
            why.describe(),
            crate::units::short(run.final_time_s),
            crate::units::short(duration_s)
        )
    })
}

/// SPL (dB) of every impact of a run, in order.
pub fn impact_spls(run: &Run, design: &ValidDesign) -> Result<Vec<f64>, ThudError> {
    run.impacts.iter().map(|i| design.impact_spl_db(i.u_in_m_s)).collect()
}
