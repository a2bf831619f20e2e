//! The result records every front end hands out: what `thud pulse|simulate|response --json`
//! print and what the Python module's `Pulse`, `Run` and `Response` objects hold, built in one
//! place so the two cannot drift (the command line serializes a record; Python converts the
//! same record into attributes and NumPy arrays).
//!
//! Each record is a plain serde struct whose field order is the JSON's key order. Building
//! one runs no solver: it gathers what an evaluation, an ensemble or a response already
//! computed (plus the SPL of each impact, Eqs 9–24, for a run's impact list).

use serde::{Deserialize, Serialize};

use crate::acoustics::{Extremum, Field, PulseShape, QuadSigns, Source};
use crate::contact::Contact;
use crate::damper::{EnergyLedger, ImpactEvent, Maximum};
use crate::design::{self, Design, Evaluation, Metrics, ValidDesign, Zone};
use crate::ensemble::{Ensemble, Member, Spread};
use crate::error::ThudError;
use crate::limits::short;
use crate::params::PulseInput;
use crate::response::{EnsembleSweep, Response, ResponseEnsemble, ResponseSweep};

/// How `spl_db` of a pulse is defined.
pub const SPL_DEFINITION: &str = "rms over one contact duration from the direct arrival";

/// A pressure waveform: times (s, from the contact's start) and pressures (Pa).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Waveform {
    pub t_s: Vec<f64>,
    pub p_pa: Vec<f64>,
}

/// One Hertzian impact heard at one observer (`thud pulse --json`, Python's `thud.pulse`): the
/// inputs as used, the contact (Eqs 5–7), the levels (dB re 20 µPa) and the waveform. SI
/// units; angles in degrees.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PulseReport {
    /// Sphere radius a (m).
    pub radius_m: f64,
    /// Sphere mass m (kg).
    pub mass_kg: f64,
    /// Impact speed U0 (m/s).
    pub u0_m_s: f64,
    /// Hertz stiffness K_HZ (N/m^1.5).
    #[serde(rename = "k_hz_n_m1_5")]
    pub k_hz: f64,
    /// Observer distance r (m).
    pub r_m: f64,
    /// Observer angle θ (degrees).
    pub theta_deg: f64,
    /// "single", "dipole" or "quadrupole".
    pub source: Source,
    /// "paper" or "rigid".
    pub quad_signs: QuadSigns,
    /// "half-sine" or "hertz".
    pub pulse: PulseShape,
    /// Air impedance ρ0·c (Pa·s/m).
    pub rho_c_pa_s_m: f64,
    /// Speed of sound c (m/s).
    pub c_m_s: f64,
    /// Peak approach α_max (m).
    pub alpha_max_m: f64,
    /// Peak acceleration A_max (m/s²).
    pub accel_max_m_s2: f64,
    /// Contact duration τ (s).
    pub tau_s: f64,
    /// Peak contact force (N).
    pub force_max_n: f64,
    /// Arrival of the direct wave (s after the contact starts).
    pub arrival_s: f64,
    /// SPL (dB), as [`SPL_DEFINITION`] says.
    pub spl_db: f64,
    pub spl_definition: String,
    /// Peak level (dB).
    pub spl_peak_db: f64,
    /// Sound exposure level (dB).
    pub sel_db: f64,
    /// rms pressure over the SPL window (Pa).
    pub p_rms_pa: f64,
    /// Largest and smallest pressure (Pa).
    pub p_max_pa: f64,
    pub p_min_pa: f64,
    /// Local extrema of the waveform after the direct arrival.
    pub extrema: Vec<Extremum>,
    /// The waveform at `points` points.
    pub waveform: Waveform,
    /// The model, written only when not the paper's: "physical", whose level is `spl_peak_db`.
    #[serde(default, skip_serializing_if = "str::is_empty")]
    pub model: String,
}

impl PulseReport {
    /// The record of the impact `input` with its `contact` and `field` (from
    /// [`PulseInput::contact`] and [`PulseInput::field`]), with a waveform of `points` points.
    #[must_use]
    pub fn new(input: &PulseInput, contact: &Contact, field: &Field, points: usize) -> Self {
        let lv = field.levels();
        let (t_s, p_pa) = field.waveform(points);
        let r = &input.radiation;
        PulseReport {
            radius_m: input.radius_m,
            mass_kg: input.impact.mass_kg,
            u0_m_s: input.impact.u0_m_s,
            k_hz: input.impact.k_hz,
            r_m: input.observer.r_m,
            theta_deg: input.observer.theta_rad.to_degrees(),
            source: r.source,
            quad_signs: r.quad_signs,
            pulse: r.pulse,
            rho_c_pa_s_m: r.air.rho_c_pa_s_m,
            c_m_s: r.air.c_m_s,
            alpha_max_m: contact.alpha_max_m,
            accel_max_m_s2: contact.accel_max_m_s2,
            tau_s: contact.tau_s,
            force_max_n: contact.force_max_n,
            arrival_s: field.arrival_s(),
            spl_db: lv.spl_db,
            spl_definition: SPL_DEFINITION.to_string(),
            spl_peak_db: lv.spl_peak_db,
            sel_db: lv.sel_db,
            p_rms_pa: lv.p_rms_pa,
            p_max_pa: lv.p_max_pa,
            p_min_pa: lv.p_min_pa,
            extrema: field.extrema(),
            waveform: Waveform { t_s, p_pa },
            model: match input.model {
                crate::design::Model::Paper => String::new(),
                m @ crate::design::Model::Physical => m.name().to_string(),
            },
        }
    }
}

/// One impact of a run as reported: the event and the SPL of its pulse at the observer.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ImpactReport {
    /// Contact onset (s).
    pub t_s: f64,
    /// The wall hit: +1 (y = +d/2) or −1.
    pub wall: i8,
    /// Relative speeds into and out of the contact (m/s).
    pub u_in_m_s: f64,
    pub u_out_m_s: f64,
    /// u_out/u_in.
    pub restitution: f64,
    /// Contact end (s) and duration (s).
    pub t_end_s: f64,
    pub duration_s: f64,
    /// Largest penetration δ (m).
    pub penetration_max_m: f64,
    /// SPL (dB) of the impact's pulse at the observer.
    pub spl_db: f64,
}

impl ImpactReport {
    fn new(i: &ImpactEvent, spl_db: f64) -> Self {
        ImpactReport {
            t_s: i.t_s,
            wall: i.wall.into(),
            u_in_m_s: i.u_in_m_s,
            u_out_m_s: i.u_out_m_s,
            restitution: i.u_out_m_s / i.u_in_m_s,
            t_end_s: i.t_end_s,
            duration_s: i.t_end_s - i.t_s,
            penetration_max_m: i.penetration_max_m,
            spl_db,
        }
    }
}

/// One damper design run through its impacts (`thud simulate --json`, Python's
/// `thud.simulate`): the metrics (Eq 27), every impact, the cycle maxima, the energy ledger
/// and, when forced, the steady state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunReport {
    /// The design as run.
    pub design: Design,
    /// Ball radius (m).
    pub ball_radius_m: f64,
    /// The metrics (Eq 27), written flat with the zone as its number 1–4.
    #[serde(flatten)]
    pub metrics: Metrics,
    pub impacts: Vec<ImpactReport>,
    pub maxima: Vec<Maximum>,
    pub energy: EnergyLedger,
    /// Time reached (s).
    pub final_time_s: f64,
    /// Whether the run stopped before its duration (a solver work cap).
    pub truncated: bool,
    /// Why, when it did.
    pub truncation_reason: Option<String>,
    /// The steady state of a forced run (absent without a force).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steady: Option<crate::response::Steady>,
}

impl RunReport {
    /// The record of `eval`, the evaluation of the design `d`.
    pub fn new(d: &ValidDesign, eval: &Evaluation) -> Result<Self, ThudError> {
        let spls = design::impact_spls(&eval.run, d)?;
        let truncation_reason = design::truncation(&eval.run, d.damper.duration_s);
        Ok(RunReport {
            design: d.design().clone(),
            ball_radius_m: d.ball_radius_m(),
            metrics: eval.metrics,
            impacts: eval.run.impacts.iter().zip(spls).map(|(i, spl)| ImpactReport::new(i, spl)).collect(),
            maxima: eval.run.maxima.clone(),
            energy: eval.run.energy,
            final_time_s: eval.run.final_time_s,
            truncated: truncation_reason.is_some(),
            truncation_reason,
            steady: eval.steady,
        })
    }
}

/// The ensemble of one design (`thud simulate --ensemble N --json`, Python's
/// `thud.simulate(ensemble=N)`): the zone of the medians, the spread, every run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnsembleReport {
    pub design: Design,
    /// Ball radius (m).
    pub ball_radius_m: f64,
    pub runs: usize,
    /// The zone of the medians (number 1–4).
    pub zone: Option<u8>,
    pub zone3_probability: f64,
    pub agreement: f64,
    pub spread: Spread,
    pub ensemble: Vec<Member>,
    /// Whether any run stopped before its duration (a solver work cap).
    pub truncated: bool,
    pub truncation_reason: Option<String>,
}

impl EnsembleReport {
    /// The record of the ensemble `e` of the design `d`.
    #[must_use]
    pub fn new(d: &Design, e: &Ensemble) -> Self {
        let cut: Vec<&Member> = e.ensemble.iter().filter(|m| m.truncated.is_some()).collect();
        let truncation_reason = (!cut.is_empty()).then(|| {
            format!(
                "{} of {} runs stopped at a solver work cap before {} s (first at y0 = {} m); their results cover only part of the run",
                cut.len(),
                e.runs,
                short(d.damper.duration_s),
                short(cut[0].ball_position_m)
            )
        });
        EnsembleReport {
            design: d.clone(),
            ball_radius_m: d.ball_radius_m(),
            runs: e.runs,
            zone: e.metrics.zone.map(Zone::number),
            zone3_probability: e.zone3_probability,
            agreement: e.agreement,
            spread: e.spread,
            ensemble: e.ensemble.clone(),
            truncated: truncation_reason.is_some(),
            truncation_reason,
        }
    }
}

/// A frequency response (`thud response --json`, Python's `thud.response`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResponseReport {
    /// The design at the first frequency (each point sets its own).
    pub design: Design,
    /// Force amplitude F0 (N).
    pub force_n: f64,
    /// Forcing periods N of each steady-state window.
    pub periods: u32,
    /// Whether each frequency started from the previous one's final state.
    pub continuation: bool,
    pub sweeps: Vec<ResponseSweep>,
}

impl ResponseReport {
    /// The record of the response `r` of the design `d`.
    #[must_use]
    pub fn new(d: &Design, r: &Response, continuation: bool) -> Self {
        ResponseReport {
            design: d.clone(),
            force_n: r.force_n,
            periods: d.damper.steady_periods,
            continuation,
            sweeps: r.sweeps.clone(),
        }
    }
}

/// A frequency response of ensembles (`thud response --ensemble N --json`, Python's
/// `thud.response(ensemble=N)`): per frequency the spread of the steady figures over the runs
/// and every run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResponseEnsembleReport {
    pub design: Design,
    pub force_n: f64,
    pub periods: u32,
    pub continuation: bool,
    /// Runs per frequency N.
    pub runs: usize,
    pub sweeps: Vec<EnsembleSweep>,
}

impl ResponseEnsembleReport {
    /// The record of the response ensemble `r` of the design `d`.
    #[must_use]
    pub fn new(d: &Design, r: &ResponseEnsemble, continuation: bool) -> Self {
        ResponseEnsembleReport {
            design: d.clone(),
            force_n: r.force_n,
            periods: d.damper.steady_periods,
            continuation,
            runs: r.runs,
            sweeps: r.sweeps.clone(),
        }
    }
}
