//! A damper design and what it is worth: damping inclination (Eq 27), peak contact speed, peak
//! SPL, zones (Figs 15–17), the design sweep over mass × gap and Table 5. Pure functions.

pub mod search;

use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::acoustics::{gauss_legendre, Field, Observer, PulseShape, QuadSigns, Radiation, Source, P_REF_PA};
use crate::contact::{self, Impact, Target};
use crate::damper::{self, DamperParams, Run, RunOptions, Solver, SteadyMotion};
use crate::error::{check_positive, ThudError};

/// How the impact mass's radius is found (it sets the sound, Eq 15, and K_HZ from materials).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BallSize {
    /// From the mass and this density (kg/m³): a = (3m/(4πρ))^(1/3). Written `density_kg_m3`,
    /// read also as `density` (thud 0.1's spelling).
    #[serde(rename = "density_kg_m3", alias = "density")]
    Density(f64),
    /// A fixed radius (m), whatever the mass. Written `radius_m`, read also as `radius`.
    #[serde(rename = "radius_m", alias = "radius")]
    Radius(f64),
}

/// Density (kg/m³) of the paper's ball: acrylic, the material its K_HZ = 5.6e8 N/m^1.5 is for
/// (acrylic on steel, Eq 2). With it Table 3's SPLmax is met to ≈ 0.6 dB rms; the density implied
/// by Fig 2's pairing of 40.5 g with 19.05 mm (1398.6 kg/m³) gives ≈ 1.3 dB rms.
pub const PAPER_BALL_DENSITY: f64 = 1190.0;

/// The least-squares contact damping (N·s/m) that reproduces Table 3 with the no-tension clamp
/// (docs/model.md §7, Table 3). The value in the `paper-table3` preset file.
pub const TABLE3_C1: f64 = 83.68;

/// Materials from which K_HZ follows for each ball radius (Eq 2), instead of a fixed K_HZ.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Materials {
    pub sphere: String,
    pub plate: String,
    /// The ball's Poisson ratio ν (dimensionless), overriding the sphere material's; absent
    /// (and not written) when the material's own applies.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sphere_nu: Option<f64>,
}

impl Materials {
    /// A ball of material `sphere` on a main mass of material `plate`, every other choice at
    /// its default (the materials' own Poisson ratios). Front ends build materials with this,
    /// so a new option here touches no front end.
    #[must_use]
    pub fn new(sphere: impl Into<String>, plate: impl Into<String>) -> Self {
        Self { sphere: sphere.into(), plate: plate.into(), sphere_nu: None }
    }

    /// The ball's material: the sphere's, with its Poisson ratio overridden by `sphere_nu`.
    pub fn sphere_material(&self) -> Result<contact::Material, ThudError> {
        let m = contact::material(&self.sphere).map_err(|e| e.renamed("sphere"))?;
        Ok(contact::Material { nu: self.sphere_nu.unwrap_or(m.nu), ..m })
    }

    /// K_HZ (N/m^1.5) of a ball of radius `radius_m` (m) of these materials, Eq 2:
    /// K_HZ = (4/3)·√R·E* with 1/E* = (1−ν1²)/E1 + (1−ν2²)/E2, ν1 the ball's ([`Self::sphere_material`]).
    pub fn hertz_stiffness(&self, radius_m: f64) -> Result<f64, ThudError> {
        Ok(contact::hertz_stiffness(
            radius_m,
            &self.sphere_material()?,
            &contact::material(&self.plate).map_err(|e| e.renamed("plate"))?,
        ))
    }
}

/// Which model of the world a design is heard through (docs/model.md §10).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Model {
    /// The paper's: the rms level over τ, the pulse, air and K_HZ as the design gives them
    /// (the half-sine, ρ0c 400 Pa·s/m unless set otherwise). Reproduces the paper.
    #[default]
    Paper,
    /// The measured world: the peak level a microphone reports, the exact Hertz pulse, air from
    /// its temperature and pressure, and K_HZ from the materials (Eq 2; acrylic on steel, the
    /// paper's pair, when none are named). No constant is fitted to the paper's Table 1.
    Physical,
}

impl Model {
    /// Every model, in the order front ends list them.
    pub const ALL: [Model; 2] = [Model::Paper, Model::Physical];

    /// The model's name, as front ends spell it.
    pub fn name(self) -> &'static str {
        match self {
            Model::Paper => "paper",
            Model::Physical => "physical",
        }
    }

    /// What the model's headline level is, for labels ("rms over τ", "peak").
    pub fn level_name(self) -> &'static str {
        match self {
            Model::Paper => "rms over τ",
            Model::Physical => "peak",
        }
    }

    fn is_paper(&self) -> bool {
        *self == Model::Paper
    }
}

/// The air's state, from which the physical model derives ρ0, c and ρ0·c
/// ([`crate::acoustics::Air::from_state`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Atmosphere {
    /// Air temperature (°C).
    pub temperature_c: f64,
    /// Air pressure (Pa).
    pub pressure_pa: f64,
}

impl Default for Atmosphere {
    /// Room air: 20 °C, 101.325 kPa.
    fn default() -> Self {
        Self {
            temperature_c: crate::acoustics::ROOM_TEMPERATURE_C,
            pressure_pa: crate::acoustics::STANDARD_PRESSURE_PA,
        }
    }
}

impl Atmosphere {
    fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

/// The materials the physical model assumes when a design names none: the paper's acrylic
/// ball on a steel structure (the pair its K_HZ = 5.6e8 N/m^1.5 and Table 1 are for).
pub const PHYSICAL_DEFAULT_SPHERE: &str = "acrylic";

/// Which largest contact speed is reported as U0max (docs/model.md §6–7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum U0MaxRule {
    /// The largest incoming relative speed of an actual impact (physical; default).
    #[default]
    Impacts,
    /// The largest |z'| over the whole run including t = 0 (the paper's Table 3).
    WholeRun,
}

/// Which damping inclination classifies the zones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ZoneBy {
    /// The paper's e of Eq 27 (first two cycle maxima).
    #[default]
    Paper,
    /// The robust least-squares e_fit.
    Fit,
}

/// The zone thresholds L* (dB) and e* (cm/s) of the design chart (docs/model.md §6).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Thresholds {
    pub spl_db: f64,
    pub inclination_cm_s: f64,
    #[serde(default)]
    pub zone_by: ZoneBy,
}

impl Default for Thresholds {
    fn default() -> Self {
        Self { spl_db: 103.0, inclination_cm_s: 0.9, zone_by: ZoneBy::Paper }
    }
}

/// One design: the damper, the ball's size and materials, the listener, the solver and the
/// conventions for the reported numbers. Everything SI.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Design {
    pub damper: DamperParams,
    pub ball: BallSize,
    /// When set, K_HZ follows from these materials and the ball's radius (Eq 2).
    #[serde(default)]
    pub materials: Option<Materials>,
    pub observer: Observer,
    pub radiation: Radiation,
    pub solver: Solver,
    #[serde(default)]
    pub u0max_rule: U0MaxRule,
    #[serde(default)]
    pub thresholds: Thresholds,
    /// The model the design is heard through (written only when not the paper's).
    #[serde(default, skip_serializing_if = "Model::is_paper")]
    pub model: Model,
    /// The air's temperature and pressure: the physical model's air (written only when not
    /// room air).
    #[serde(default, skip_serializing_if = "Atmosphere::is_default")]
    pub atmosphere: Atmosphere,
}

impl Default for Design {
    /// The physical default: Table 2 (Fig 9: v0 2 m/s, d 4 cm), an acrylic ball (the paper's), the
    /// rigid wall–floor corner at r 0.7 m, θ 45°, the event-driven solver.
    fn default() -> Self {
        Self {
            damper: DamperParams::table2(),
            ball: BallSize::Density(PAPER_BALL_DENSITY),
            materials: None,
            observer: Observer::new(0.7, 45.0),
            radiation: Radiation { source: Source::Quadrupole, quad_signs: QuadSigns::Rigid, ..Default::default() },
            solver: Solver::Event,
            u0max_rule: U0MaxRule::Impacts,
            thresholds: Thresholds::default(),
            model: Model::Paper,
            atmosphere: Atmosphere::default(),
        }
    }
}

impl Design {
    /// The paper's Fig 9 set-up: the default design heard through the paper's quadrupole signs
    /// (the `paper-fig9` preset; the app's preset tests check that the file says the same).
    #[must_use]
    pub fn paper_fig9() -> Self {
        Self {
            radiation: Radiation { source: Source::Quadrupole, quad_signs: QuadSigns::Paper, ..Default::default() },
            ..Self::default()
        }
    }

    /// The set-up that reproduces Table 3 (the `paper-table3` preset): Fig 9's with v0 1.4 m/s,
    /// c1 = [`TABLE3_C1`] with the no-tension clamp and U0max over the whole run.
    #[must_use]
    pub fn paper_table3() -> Self {
        let mut d = Self::paper_fig9();
        d.damper.v0_m_s = 1.4;
        d.damper.c1_n_s_m = TABLE3_C1;
        d.damper.no_tension = true;
        d.u0max_rule = U0MaxRule::WholeRun;
        d
    }

    /// Radius of the impact mass (m).
    pub fn ball_radius_m(&self) -> f64 {
        match self.ball {
            BallSize::Density(rho) => contact::sphere_radius(self.damper.impact_mass_kg, rho),
            BallSize::Radius(a) => a,
        }
    }

    /// The materials K_HZ follows from: the design's own, or with the physical model and none
    /// named, the paper's acrylic ball on steel ([`PHYSICAL_DEFAULT_SPHERE`]).
    pub fn materials_used(&self) -> Option<Materials> {
        match (&self.materials, self.model) {
            (Some(m), _) => Some(m.clone()),
            (None, Model::Physical) => Some(Materials::new(PHYSICAL_DEFAULT_SPHERE, "steel")),
            (None, Model::Paper) => None,
        }
    }

    /// The Hertz stiffness K_HZ (N/m^1.5) this design runs with: from its materials for the
    /// ball's current radius (Eq 2) when it has materials ([`Design::materials_used`]), else
    /// its own `k_hz`.
    pub fn hertz_stiffness(&self) -> Result<f64, ThudError> {
        match self.materials_used() {
            Some(m) => m.hertz_stiffness(self.ball_radius_m()),
            None => Ok(self.damper.k_hz),
        }
    }

    /// The radiation the sound is computed with: the design's own with the paper's model; with
    /// the physical model, the exact Hertz pulse and the air of [`Design::atmosphere`]
    /// ([`crate::acoustics::Air::from_state`]), the source and its signs as the design says.
    pub fn sound(&self) -> Radiation {
        match self.model {
            Model::Paper => self.radiation,
            Model::Physical => Radiation {
                pulse: PulseShape::Hertz,
                air: crate::acoustics::Air::from_state(self.atmosphere.temperature_c, self.atmosphere.pressure_pa),
                ..self.radiation
            },
        }
    }

    /// The headline level (dB re 20 µPa) of an impact's `field` under this design's model: the
    /// paper's rms over τ from the direct arrival (Table 1's convention), or with the physical
    /// model the peak level 20·log10(max|p|/20 µPa) a microphone's peak reading gives.
    pub fn level_db(&self, field: &Field) -> f64 {
        match self.model {
            Model::Paper => field.spl_db(),
            Model::Physical => field.peak_db(),
        }
    }

    /// Checks every parameter; the first problem is reported, naming the CLI parameter.
    /// Part of [`Design::check`] (beside the range table, in [`crate::limits`]), which also
    /// checks the ranges and resolves K_HZ.
    pub fn validate(&self) -> Result<(), ThudError> {
        self.damper.validate()?;
        match self.ball {
            BallSize::Density(rho) => check_positive("density", rho, "kg/m^3")?,
            BallSize::Radius(a) => check_positive("radius", a, "m")?,
        }
        if let Solver::Newmark { dt_s } = self.solver {
            check_positive("dt", dt_s, "s")?;
        }
        self.sound().air.validate()?;
        crate::acoustics::validate_observer(self.ball_radius_m(), &self.observer, self.radiation.source)?;
        if !self.thresholds.spl_db.is_finite() || !self.thresholds.inclination_cm_s.is_finite() {
            return Err(ThudError::invalid("thresholds", "L* and e* must be finite numbers"));
        }
        Ok(())
    }

    /// The sound field of one impact of this design at incoming relative speed `u0` (m/s):
    /// the ball against the main mass, K* = (m+M)/(mM) (Eq 8).
    pub fn impact_field(&self, u0: f64) -> Result<Field, ThudError> {
        let impact = Impact {
            mass_kg: self.damper.impact_mass_kg,
            u0_m_s: u0,
            k_hz: self.damper.k_hz,
            target: Target::MovableMass(self.damper.main_mass_kg),
        };
        impact.validate()?;
        Field::new(self.ball_radius_m(), &impact.contact(), &self.observer, &self.sound())
    }

    /// The headline level (dB) of an impact at `u0` (m/s): the paper's SPL (rms over τ from
    /// the direct arrival) or the physical model's peak level ([`Design::level_db`]).
    pub fn impact_spl_db(&self, u0: f64) -> Result<f64, ThudError> {
        Ok(self.level_db(&self.impact_field(u0)?))
    }
}

/// A design that passed [`Design::check`]: every range of the range table, the
/// cross-checks (|y0| < d/2, the observer outside the ball, finite thresholds, …) and K_HZ
/// resolved from its materials for its radius. Only the engine builds one ([`Design::check`],
/// the named-parameter builder [`crate::params::design`], and a chart's cells), and
/// every solver and evaluation takes one ([`evaluate`], [`sweep`], [`crate::ensemble`],
/// [`crate::response`], the work checks of [`crate::limits`]), so an unchecked or unresolved
/// design cannot reach a solver.
///
/// Read it as a [`Design`] (it dereferences to one). To change it, take the design out
/// ([`ValidDesign::into_design`] or a clone), change it and check it again. It is written as
/// the design it holds; reading one (serde) checks it, so a file cannot skip the check.
///
/// Neither a struct literal nor a bare [`Design`] makes one:
///
/// ```compile_fail
/// use thud_core::design::{Design, ValidDesign};
/// let v = ValidDesign(Design::default());
/// ```
///
/// ```compile_fail
/// use thud_core::design::{Design, ValidDesign};
/// let v: ValidDesign = Design::default().into();
/// ```
///
/// ```compile_fail
/// use thud_core::design::{self, Design};
/// // A solver takes only a checked design.
/// let e = design::evaluate(&Design::default(), 0, None);
/// ```
///
/// ```
/// use thud_core::design::{self, Design};
/// let v = Design::default().check().unwrap();
/// let e = design::evaluate(&v, 0, None).unwrap();
/// assert!(e.metrics.n_impacts > 0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ValidDesign(Design);

impl ValidDesign {
    /// The checked design (K_HZ resolved).
    #[must_use]
    pub fn design(&self) -> &Design {
        &self.0
    }

    /// The design, to change and check again.
    #[must_use]
    pub fn into_design(self) -> Design {
        self.0
    }

    /// `d`, whose ranges [`Design::check`] has checked, after the physics' own checks
    /// ([`Design::validate`]) with K_HZ set from its materials for its radius: the one
    /// constructor, called by [`Design::check`] after the range table, and for a chart cell.
    pub(crate) fn from_ranges_checked(d: Design) -> Result<ValidDesign, ThudError> {
        d.validate()?;
        let mut d = d;
        d.damper.k_hz = d.hertz_stiffness()?;
        Ok(ValidDesign(d))
    }

    /// This design with impact mass `mass_kg` and gap `gap_m` (a chart cell or a restitution
    /// curve's mass), checked again by the physics' own checks with K_HZ resolved again: the
    /// ball's radius, and with it K_HZ from the materials and the observer's distance to the
    /// ball, follow the mass, and |y0| < d/2 the gap. The range table is not run again: every
    /// front end checks the axes against the mass and gap ranges (the sweep itself that they
    /// are > 0), and every mass and density inside their ranges gives a radius, and with
    /// materials a K_HZ, inside theirs ([`crate::limits::RADIUS`], [`crate::limits::K_HZ`]);
    /// nothing else changes. These checks are what [`evaluate`] ran on every cell before it
    /// took a checked design.
    pub(crate) fn variant(&self, mass_kg: f64, gap_m: f64) -> Result<ValidDesign, ThudError> {
        ValidDesign::from_ranges_checked(variant(self, mass_kg, gap_m))
    }
}

impl std::ops::Deref for ValidDesign {
    type Target = Design;

    fn deref(&self) -> &Design {
        &self.0
    }
}

impl From<ValidDesign> for Design {
    fn from(v: ValidDesign) -> Design {
        v.0
    }
}

impl PartialEq<Design> for ValidDesign {
    fn eq(&self, other: &Design) -> bool {
        self.0 == *other
    }
}

impl Serialize for ValidDesign {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

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

/// What one design is worth.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
/// ([`SteadyMotion`]) and the level of the rattle over it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Steady {
    /// Forcing periods N in the window.
    pub periods: u32,
    /// The window (s).
    pub window_start_s: f64,
    pub window_end_s: f64,
    /// Largest |x| in the window (m).
    pub amplitude_m: f64,
    /// The main mass without the ball: `F0/√((K − MΩ²)² + (CΩ)²)` (m); None where unbounded.
    pub amplitude_linear_m: Option<f64>,
    /// `20·log10(amplitude_linear/amplitude)` (dB, > 0 when the damper cuts the amplitude).
    pub reduction_db: Option<f64>,
    /// Impacts per forcing period in the window.
    pub impacts_per_period: f64,
    /// Energy-average level at the observer over the window (dB re 20 µPa); None when no
    /// impact sounds in it.
    pub leq_db: Option<f64>,
    /// Whether x repeats from period to period within 1e-3 of the amplitude.
    pub periodic: bool,
    /// Whether the amplitude of the window is within 1e-3 of the window before's.
    pub settled: bool,
    /// Whether a work cap stopped the run before the window's end.
    pub truncated: bool,
    /// The verdict on the motion ([`crate::verdict`]): what every surface says of it.
    #[serde(default)]
    pub verdict: crate::verdict::Verdict,
}

/// The steady state of `run` of `design`, if the design is forced.
pub fn steady(run: &Run, design: &ValidDesign) -> Result<Option<Steady>, ThudError> {
    run_steady(run, design)
}

/// [`steady`] of a run of a design derived from a [`ValidDesign`] (resolved and valid: a
/// response's design at one frequency).
pub(crate) fn run_steady(run: &Run, design: &Design) -> Result<Option<Steady>, ThudError> {
    let Some(m) = run.steady else { return Ok(None) };
    Ok(Some(with_level(&m, run_leq_db(run, design, m.window_start_s, m.window_end_s)?)))
}

fn with_level(m: &SteadyMotion, leq_db: Option<f64>) -> Steady {
    Steady {
        periods: m.periods,
        window_start_s: m.window_start_s,
        window_end_s: m.window_end_s,
        amplitude_m: m.amplitude_m,
        amplitude_linear_m: m.amplitude_linear_m,
        reduction_db: m.reduction_db,
        impacts_per_period: m.impacts_per_period,
        leq_db,
        periodic: m.periodic,
        settled: m.settled,
        truncated: m.truncated,
        verdict: m.verdict,
    }
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

/// `n` evenly spaced values from `from` to `to` inclusive.
pub fn linspace(from: f64, to: f64, n: usize) -> Vec<f64> {
    match n {
        0 => vec![],
        1 => vec![from],
        _ => (0..n).map(|i| from + (to - from) * i as f64 / (n - 1) as f64).collect(),
    }
}

/// One cell of the design chart.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    pub mass_kg: f64,
    pub gap_m: f64,
    pub metrics: Metrics,
}

/// The design chart: a mass × gap grid of metrics. `cells[g * masses.len() + m]` is gap `g`,
/// mass `m`; a cell is None until computed (or if the sweep was cancelled first).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Chart {
    pub masses_kg: Vec<f64>,
    pub gaps_m: Vec<f64>,
    pub cells: Vec<Option<Cell>>,
    pub thresholds: Thresholds,
}

impl Chart {
    pub fn empty(masses_kg: Vec<f64>, gaps_m: Vec<f64>, thresholds: Thresholds) -> Self {
        let n = masses_kg.len() * gaps_m.len();
        Self { masses_kg, gaps_m, cells: vec![None; n], thresholds }
    }

    pub fn cell(&self, mass_index: usize, gap_index: usize) -> Option<&Cell> {
        self.cells.get(gap_index * self.masses_kg.len() + mass_index)?.as_ref()
    }

    pub fn done(&self) -> usize {
        self.cells.iter().filter(|c| c.is_some()).count()
    }
}

/// The design `base` with this impact mass and gap, unchecked (a chart cell's parameters, or
/// a key; [`sweep`] checks each cell again).
pub fn variant(base: &Design, mass_kg: f64, gap_m: f64) -> Design {
    let mut d = base.clone();
    d.damper.impact_mass_kg = mass_kg;
    d.damper.gap_m = gap_m;
    d
}

/// Sweeps `base` over `masses × gaps` on rayon's global thread pool (one pool for the whole
/// process, so sweeps running at once share the cores instead of each taking all of them).
/// `on_cell(index, cell)` is called as each cell finishes (from pool threads, in no particular
/// order); `cancel` stops the sweep between cells (cells not started stay `None`). The chart
/// does not depend on the scheduling; the first failing cell (in index order) gives the error.
/// A panic in a cell (or in `on_cell`) propagates to the caller. Each cell is `base` at its
/// (mass, gap) checked again by the physics' own checks ([`Design::validate`]) with K_HZ
/// resolved again: the axes do not make a cell valid (K_HZ from materials and the observer's
/// distance follow the ball's radius, |y0| < d/2 the gap). The axes' ranges are the caller's
/// to check (every front end checks them against the mass and gap ranges; here they must be
/// > 0); inside them the derived radius and K_HZ stay inside their ranges.
pub fn sweep(
    base: &ValidDesign,
    masses_kg: &[f64],
    gaps_m: &[f64],
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &Cell) + Sync),
) -> Result<Chart, ThudError> {
    let n = masses_kg.len() * gaps_m.len();
    let cells = sweep_cells(base, masses_kg, gaps_m, 0..n, cancel, on_cell)?;
    let mut chart = Chart::empty(masses_kg.to_vec(), gaps_m.to_vec(), base.thresholds);
    for (i, cell) in cells {
        chart.cells[i] = Some(cell);
    }
    Ok(chart)
}

/// The cells `range` of the chart [`sweep`] would compute (row-major indices, `g·masses + m`),
/// as `(index, cell)` in index order: the part of the chart one shard computes. Scheduling,
/// cancellation, errors and panics as in [`sweep`] (a cancelled run returns the cells it
/// finished). Indices past the grid are ignored.
pub fn sweep_cells(
    base: &ValidDesign,
    masses_kg: &[f64],
    gaps_m: &[f64],
    range: Range<usize>,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &Cell) + Sync),
) -> Result<Vec<(usize, Cell)>, ThudError> {
    grid_cells(masses_kg, gaps_m, range, cancel, on_cell, |mass_kg, gap_m| {
        let cell = base.variant(mass_kg, gap_m).and_then(|d| evaluate(&d, 0, cancel));
        Some(cell.map(|e| Cell { mass_kg, gap_m, metrics: e.metrics }))
    })
}

/// The cells `range` (row-major indices) of a mass × gap grid, each `cell(mass, gap)` evaluated
/// on rayon's global pool, as `(index, cell)` in index order: the one scheduling of the plain
/// and the ensemble charts. `cell` returns `None` for a cell it gave up on (cancelled); a cell
/// is not started once `cancel` is set. `on_cell` sees each good cell as it finishes; the first
/// failing cell in index order gives the error; a panic propagates.
pub(crate) fn grid_cells<C: Send>(
    masses_kg: &[f64],
    gaps_m: &[f64],
    range: Range<usize>,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &C) + Sync),
    cell: impl Fn(f64, f64) -> Option<Result<C, ThudError>> + Sync,
) -> Result<Vec<(usize, C)>, ThudError> {
    check_grid(masses_kg, gaps_m)?;
    let range = range.start..range.end.min(masses_kg.len() * gaps_m.len());
    // `par_bridge` hands the cells out in index order as threads come free, so the chart fills
    // row by row and a cancelled sweep leaves (about) a prefix.
    let mut results: Vec<(usize, Result<C, ThudError>)> = range
        .par_bridge()
        .filter_map(|i| {
            if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return None;
            }
            let (mass_kg, gap_m) = grid_point(masses_kg, gaps_m, i);
            let c = cell(mass_kg, gap_m)?;
            if let Ok(c) = &c {
                on_cell(i, c);
            }
            Some((i, c))
        })
        .collect();
    results.sort_unstable_by_key(|&(i, _)| i);
    results.into_iter().map(|(i, c)| Ok((i, c?))).collect()
}

/// Checks the axes of a chart: every mass and gap finite and > 0.
pub(crate) fn check_grid(masses_kg: &[f64], gaps_m: &[f64]) -> Result<(), ThudError> {
    for &m in masses_kg {
        check_positive("mass", m, "kg")?;
    }
    for &g in gaps_m {
        check_positive("gap", g, "m")?;
    }
    Ok(())
}

/// The (mass kg, gap m) of the chart cell with row-major index `i` (`g·masses + m`).
pub(crate) fn grid_point(masses_kg: &[f64], gaps_m: &[f64], i: usize) -> (f64, f64) {
    (masses_kg[i % masses_kg.len()], gaps_m[i / masses_kg.len()])
}

/// The cells of part `k` (0-based) of `n` equal parts of a chart of `cells` cells: the
/// contiguous row-major indices `⌊k·cells/n⌋ .. ⌊(k+1)·cells/n⌋`. The parts cover every cell
/// once, in order, and differ in size by at most one cell; each is non-empty when
/// `n ≤ cells`. `k < n` and `n > 0` are the caller's to check (the result is empty otherwise).
#[must_use]
pub fn shard_range(cells: usize, k: usize, n: usize) -> Range<usize> {
    if n == 0 || k >= n {
        return 0..0;
    }
    // u128: k·cells cannot overflow.
    let at = |j: usize| (j as u128 * cells as u128 / n as u128) as usize;
    at(k)..at(k + 1)
}

/// One band of Table 5: the spread of SPLmax among designs with e in [e_lo, e_hi).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Band {
    pub e_lo_cm_s: f64,
    pub e_hi_cm_s: f64,
    pub count: usize,
    pub spl_min_db: f64,
    pub spl_max_db: f64,
}

/// The smallest and largest inclination (cm/s, by `zone_by`) among the cells Table 5 bands:
/// those with both that inclination and an SPLmax. None when there are none.
pub fn inclination_span(chart: &Chart, zone_by: ZoneBy) -> Option<(f64, f64)> {
    let es: Vec<f64> = chart
        .cells
        .iter()
        .flatten()
        .filter(|c| c.metrics.spl_max_db.is_some())
        .filter_map(|c| c.metrics.inclination_by(zone_by))
        .collect();
    let lo = es.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = es.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (!es.is_empty()).then_some((lo, hi))
}

/// Table 5: the range of SPLmax per band of the inclination (cm/s) of width `width_cm_s`.
pub fn spl_range_by_inclination(chart: &Chart, width_cm_s: f64, zone_by: ZoneBy) -> Vec<Band> {
    let pts: Vec<(f64, f64)> = chart
        .cells
        .iter()
        .flatten()
        .filter_map(|c| Some((c.metrics.inclination_by(zone_by)?, c.metrics.spl_max_db?)))
        .collect();
    if pts.is_empty() || width_cm_s.is_nan() || width_cm_s <= 0.0 {
        return vec![];
    }
    let lo = (pts.iter().map(|p| p.0).fold(f64::INFINITY, f64::min) / width_cm_s).floor() as i64;
    let hi = (pts.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max) / width_cm_s).floor() as i64;
    // Only the bands a point can fall in (its k = ⌊e/w⌋ and the neighbours rounding may put it
    // in) are visited, each by bisection, so the work is O(n log n) in the points however wide
    // the span (a forced chart's e spans 1e7 cm/s; a merge under --no-limit must not hang):
    // the same bands, in the same order, as scanning every k from lo to hi.
    let mut candidates: Vec<i64> = pts
        .iter()
        .flat_map(|p| {
            let k = (p.0 / width_cm_s).floor() as i64;
            [k.saturating_sub(1), k, k.saturating_add(1)]
        })
        .filter(|k| (lo..=hi).contains(k))
        .collect();
    candidates.sort_unstable();
    candidates.dedup();
    let mut sorted = pts;
    sorted.sort_by(|x, y| x.0.total_cmp(&y.0));
    candidates
        .into_iter()
        .filter_map(|k| {
            let (a, b) = (k as f64 * width_cm_s, (k + 1) as f64 * width_cm_s);
            // The points with a ≤ e < b, found by bisection in the sorted points.
            let (from, to) = (sorted.partition_point(|p| p.0 < a), sorted.partition_point(|p| p.0 < b));
            let in_band: Vec<f64> = sorted[from..to.max(from)].iter().map(|p| p.1).collect();
            (!in_band.is_empty()).then(|| Band {
                e_lo_cm_s: a,
                e_hi_cm_s: b,
                count: in_band.len(),
                spl_min_db: in_band.iter().copied().fold(f64::INFINITY, f64::min),
                spl_max_db: in_band.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            })
        })
        .collect()
}

/// Restitution R = u_out/u0 of one isolated ball–main-mass contact at `u0` for each mass
/// (Fig 13), with the design's K_HZ (or materials), c1 and clamp.
pub fn restitution_curve(design: &ValidDesign, masses_kg: &[f64], u0: f64) -> Result<Vec<(f64, f64)>, ThudError> {
    check_positive("u0", u0, "m/s")?;
    masses_kg
        .iter()
        .map(|&m| {
            check_positive("mass", m, "kg")?;
            let d = design.variant(m, design.damper.gap_m)?;
            let p = &d.damper;
            let c = damper::single_contact(m, p.main_mass_kg, p.k_hz, p.c1_n_s_m, p.no_tension, u0);
            Ok((m, c.u_out_m_s / u0))
        })
        .collect()
}

/// The contact damping c1 (N·s/m) that gives the restitution `r` to one isolated contact of
/// this design's ball against its main mass at `u0` (the inverse of [`restitution_curve`]).
pub fn c1_for_restitution(design: &ValidDesign, u0: f64, r: f64) -> Result<f64, ThudError> {
    let p = &design.damper;
    damper::c1_for_restitution(p.impact_mass_kg, p.main_mass_kg, p.k_hz, p.no_tension, u0, r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::damper::Maximum;

    fn maxima(xs: &[(f64, f64)]) -> Vec<Maximum> {
        xs.iter().map(|&(t_s, x_m)| Maximum { t_s, x_m }).collect()
    }

    #[test]
    fn eq27_from_first_two_maxima() {
        let m = maxima(&[(0.05, 0.06), (0.25, 0.058), (0.45, 0.05)]);
        assert!((inclination_cm_s(&m).unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn fit_of_a_straight_decay_is_its_slope() {
        let m = maxima(&(0..10).map(|k| (0.2 * f64::from(k), 0.06 - 0.004 * f64::from(k))).collect::<Vec<_>>());
        // Slope −0.02 m/s = 2 cm/s; stops below X1/2 = 0.03 (k > 7).
        assert!((inclination_fit_cm_s(&m).unwrap() - 2.0).abs() < 1e-9);
        assert!(inclination_fit_cm_s(&m[..1]).is_none());
    }

    #[test]
    fn zones_by_thresholds() {
        let t = Thresholds { spl_db: 100.0, inclination_cm_s: 1.0, zone_by: ZoneBy::Paper };
        assert_eq!(Zone::classify(101.0, 0.5, &t), Zone::NoisyWeak);
        assert_eq!(Zone::classify(101.0, 1.5, &t), Zone::NoisyStrong);
        assert_eq!(Zone::classify(99.0, 1.5, &t), Zone::QuietStrong);
        assert_eq!(Zone::classify(99.0, 0.5, &t), Zone::QuietWeak);
    }

    fn metrics_with(e: Option<f64>, e_fit: Option<f64>, spl: Option<f64>) -> Metrics {
        Metrics {
            n_impacts: 3,
            inclination_cm_s: e,
            inclination_fit_cm_s: e_fit,
            u0_max_m_s: 1.0,
            zdot_abs_max_m_s: 1.0,
            spl_max_db: spl,
            contact_duration_s: None,
            restitution_mean: None,
            zone: None,
        }
    }

    #[test]
    fn zone_uses_the_inclination_the_thresholds_name() {
        let m = metrics_with(Some(0.5), Some(1.5), Some(101.0));
        assert_eq!(m.inclination_by(ZoneBy::Paper), Some(0.5));
        assert_eq!(m.inclination_by(ZoneBy::Fit), Some(1.5));
        let paper = Thresholds { spl_db: 100.0, inclination_cm_s: 1.0, zone_by: ZoneBy::Paper };
        let fit = Thresholds { zone_by: ZoneBy::Fit, ..paper };
        assert_eq!(m.zone(&paper), Some(Zone::NoisyWeak), "e 0.5 < e* 1");
        assert_eq!(m.zone(&fit), Some(Zone::NoisyStrong), "e_fit 1.5 ≥ e* 1");
        assert_eq!(metrics_with(Some(0.5), None, Some(101.0)).zone(&fit), None, "no e_fit: no zone by it");
        assert_eq!(metrics_with(Some(0.5), None, Some(101.0)).zone(&paper), Some(Zone::NoisyWeak));
        assert_eq!(metrics_with(Some(0.5), Some(1.5), None).zone(&paper), None, "no sound: no zone");
    }

    #[test]
    fn evaluated_zone_is_the_zone_under_the_design_thresholds() {
        for zone_by in [ZoneBy::Paper, ZoneBy::Fit] {
            let mut d = Design::default();
            d.thresholds.zone_by = zone_by;
            let m = evaluate(&d.clone().check().unwrap(), 0, None).unwrap().metrics;
            assert!(m.zone.is_some(), "the default design sounds and decays");
            assert_eq!(m.zone, m.zone(&d.thresholds));
            let e = m.inclination_by(zone_by).unwrap();
            // e* moved to the other side of e: strong becomes weak or weak strong.
            let e_star = if e >= d.thresholds.inclination_cm_s { e + 1.0 } else { e - 1.0 };
            let flipped = Thresholds { inclination_cm_s: e_star, ..d.thresholds };
            assert_ne!(m.zone(&flipped), m.zone, "e* across e changes the zone");
        }
    }

    #[test]
    fn paper_density_is_the_acrylic_of_the_materials_table() {
        assert_eq!(contact::material("acrylic").unwrap().density_kg_m3, PAPER_BALL_DENSITY);
    }

    #[test]
    fn c1_for_restitution_inverts_the_curve() {
        let d = Design::default().check().unwrap();
        let c1 = c1_for_restitution(&d, 1.4, 0.8).unwrap();
        let mut d2 = d.clone().into_design();
        d2.damper.c1_n_s_m = c1;
        let r = restitution_curve(&d2.check().unwrap(), &[d.damper.impact_mass_kg], 1.4).unwrap()[0].1;
        assert!((r - 0.8).abs() < 1e-6, "{r}");
        assert!(c1_for_restitution(&d, 1.4, 1.5).is_err());
    }

    /// A small chart: four cells of short runs.
    fn small_sweep(on_cell: &(dyn Fn(usize, &Cell) + Sync), cancel: Option<&AtomicBool>) -> Result<Chart, ThudError> {
        let mut d = Design::default();
        d.damper.duration_s = 0.1;
        sweep(&d.check().unwrap(), &[0.03, 0.06], &[0.02, 0.04], cancel, on_cell)
    }

    #[test]
    fn sweep_is_the_cells_evaluated_one_by_one() {
        let seen = std::sync::atomic::AtomicUsize::new(0);
        let chart = small_sweep(
            &|_, _| {
                seen.fetch_add(1, Ordering::Relaxed);
            },
            None,
        )
        .unwrap();
        assert_eq!(seen.into_inner(), 4);
        assert_eq!(chart.done(), 4);
        let mut d = Design::default();
        d.damper.duration_s = 0.1;
        for (g, &gap) in chart.gaps_m.iter().enumerate() {
            for (m, &mass) in chart.masses_kg.iter().enumerate() {
                let alone = evaluate(&variant(&d, mass, gap).check().unwrap(), 0, None).unwrap().metrics;
                assert_eq!(chart.cell(m, g).unwrap().metrics, alone, "mass {mass}, gap {gap}");
            }
        }
    }

    #[test]
    fn a_cancelled_sweep_starts_no_cell() {
        let stop = AtomicBool::new(true);
        let chart = small_sweep(&|_, _| panic!("no cell may finish"), Some(&stop)).unwrap();
        assert_eq!(chart.done(), 0);
    }

    /// A panic inside one cell (here in its progress callback, which runs in the cell's task)
    /// reaches the caller instead of leaving a hole in an `Ok` chart.
    #[test]
    fn a_panicking_cell_propagates() {
        let caught = std::panic::catch_unwind(|| {
            small_sweep(
                &|i, _| {
                    assert!(i != 2, "cell 2 failed");
                },
                None,
            )
        });
        let payload = caught.expect_err("the panic must propagate out of the sweep");
        assert_eq!(payload.downcast_ref::<&str>(), Some(&"cell 2 failed"));
    }

    #[test]
    fn shards_cover_every_cell_once_in_order() {
        for cells in [1usize, 2, 7, 400, 401] {
            for n in 1..=cells.min(70) {
                let parts: Vec<Range<usize>> = (0..n).map(|k| shard_range(cells, k, n)).collect();
                assert_eq!(parts[0].start, 0);
                assert_eq!(parts[n - 1].end, cells);
                for w in parts.windows(2) {
                    assert_eq!(w[0].end, w[1].start, "{cells} cells, {n} parts: contiguous");
                }
                let (lo, hi) = (
                    parts.iter().map(std::iter::ExactSizeIterator::len).min(),
                    parts.iter().map(std::iter::ExactSizeIterator::len).max(),
                );
                assert!(lo.unwrap() >= 1 && hi.unwrap() - lo.unwrap() <= 1, "{cells}/{n}: {lo:?}..{hi:?}");
            }
        }
        assert_eq!(shard_range(10, 3, 3), 0..0, "k ≥ n is no part");
        assert_eq!(shard_range(10, 0, 0), 0..0);
    }

    #[test]
    fn a_sweep_split_into_parts_is_the_whole_sweep() {
        let mut d = Design::default();
        d.damper.duration_s = 0.1;
        let d = d.check().unwrap();
        let (masses, gaps) = ([0.03, 0.05, 0.07], [0.02, 0.04]);
        let whole = sweep(&d, &masses, &gaps, None, &|_, _| {}).unwrap();
        let mut joined = Chart::empty(masses.to_vec(), gaps.to_vec(), d.thresholds);
        for k in 0..4 {
            for (i, c) in sweep_cells(&d, &masses, &gaps, shard_range(6, k, 4), None, &|_, _| {}).unwrap() {
                assert!(joined.cells[i].replace(c).is_none(), "cell {i} twice");
            }
        }
        assert_eq!(joined, whole);
    }

    /// A design with `f` applied, checked: the name of the parameter the check refuses.
    fn refused(f: impl FnOnce(&mut Design)) -> String {
        let mut d = Design::default();
        f(&mut d);
        d.check().unwrap_err().param().to_string()
    }

    #[test]
    fn check_refuses_a_ball_outside_the_clearance_a_nan_and_an_out_of_range_value() {
        assert_eq!(refused(|d| d.damper.ball_position_m = 0.5 * d.damper.gap_m), "ball-position", "|y0| = d/2");
        assert_eq!(refused(|d| d.damper.ball_position_m = -0.03), "ball-position", "|y0| > d/2 (d 4 cm)");
        assert_eq!(refused(|d| d.damper.v0_m_s = f64::NAN), "v0");
        assert_eq!(refused(|d| d.thresholds.spl_db = f64::NAN), "thresholds");
        // Positive and finite, so the physics' own checks pass it; the range table does not.
        assert_eq!(refused(|d| d.damper.main_mass_kg = 1e7), "main-mass");
        assert_eq!(refused(|d| d.damper.freq_hz = 1e6), "freq");
        assert_eq!(refused(|d| d.observer.theta_rad = 120f64.to_radians()), "theta", "behind the corner's wall");
        let inside = Design::default().check().unwrap();
        assert!(inside.damper.ball_position_m.abs() < 0.5 * inside.damper.gap_m);
    }

    #[test]
    fn check_resolves_k_hz_from_the_materials_for_the_balls_radius() {
        let rho = contact::material("nylon").unwrap().density_kg_m3;
        let mut d = Design {
            materials: Some(Materials { sphere: "nylon".into(), plate: "steel".into(), sphere_nu: None }),
            ball: BallSize::Density(rho),
            ..Design::default()
        };
        d.damper.k_hz = 1.0; // stale: the materials decide
        let v = d.clone().check().unwrap();
        let (nylon, steel) = (contact::material("nylon").unwrap(), contact::material("steel").unwrap());
        let radius = (3.0 * d.damper.impact_mass_kg / (4.0 * std::f64::consts::PI * rho)).cbrt();
        let want = contact::hertz_stiffness(radius, &nylon, &steel);
        assert!((v.damper.k_hz - want).abs() <= 1e-12 * want, "{} vs {want}", v.damper.k_hz);
        // A chart cell of another mass has another radius and so another K_HZ.
        let heavy = v.variant(4.0 * d.damper.impact_mass_kg, d.damper.gap_m).unwrap();
        let want_heavy = contact::hertz_stiffness(radius * 4f64.cbrt(), &nylon, &steel);
        assert!((heavy.damper.k_hz - want_heavy).abs() <= 1e-12 * want_heavy);
        assert!(heavy.damper.k_hz > v.damper.k_hz, "a bigger ball is stiffer (Eq 2)");
        // Without materials K_HZ is the design's own.
        assert_eq!(Design::default().check().unwrap().damper.k_hz, Design::default().damper.k_hz);
        // And a changed design is a Design again, to check again.
        let mut back = v.into_design();
        back.damper.ball_position_m = 1.0;
        assert_eq!(back.check().unwrap_err().param(), "ball-position");
    }

    #[test]
    fn the_balls_poisson_ratio_overrides_its_materials_in_eq_2() {
        let radius: f64 = 0.01905 / 2.0;
        let with = |sphere_nu| Materials { sphere: "steel".into(), plate: "steel".into(), sphere_nu };
        // Eq 2 from the handbook numbers: steel E 210 GPa, ν 0.30; the ball's ν 0.28.
        let (e_s, e_p, nu_s, nu_p) = (210e9, 210e9, 0.28, 0.30);
        let want = 4.0 / 3.0 * radius.sqrt() / ((1.0 - nu_s * nu_s) / e_s + (1.0 - nu_p * nu_p) / e_p);
        let k = with(Some(nu_s)).hertz_stiffness(radius).unwrap();
        assert!((k - want).abs() <= 1e-12 * want, "{k} vs {want}");
        let own = with(None).hertz_stiffness(radius).unwrap();
        assert!(k < own, "a smaller ν is a more compliant contact: {k} vs {own}");
        // The material's own ν as the override is the material: the same K_HZ to the bit.
        for m in contact::MATERIALS {
            let pair = |sphere_nu| Materials { sphere: m.name.into(), plate: "brass".into(), sphere_nu };
            let (given, plain) = (pair(Some(m.nu)).hertz_stiffness(radius), pair(None).hertz_stiffness(radius));
            assert_eq!(given.unwrap().to_bits(), plain.unwrap().to_bits(), "{}", m.name);
        }
        // A design checks and resolves it, and refuses it out of its range by name.
        let mut d = Design { materials: Some(with(Some(nu_s))), ..Design::default() };
        let v = d.clone().check().unwrap();
        let want = with(Some(nu_s)).hertz_stiffness(d.ball_radius_m()).unwrap();
        assert_eq!(v.damper.k_hz.to_bits(), want.to_bits());
        d.materials = Some(with(Some(0.7)));
        assert_eq!(d.check().unwrap_err().param(), "sphere-poisson");
    }

    #[test]
    fn no_poisson_ratio_is_written_unless_one_is_given() {
        let d = Design {
            materials: Some(Materials { sphere: "glass".into(), plate: "steel".into(), sphere_nu: None }),
            ..Design::default()
        };
        let text = serde_json::to_string(&d).unwrap();
        assert!(text.contains(r#""materials":{"sphere":"glass","plate":"steel"}"#), "{text}");
        let mut m = d.materials.clone().unwrap();
        m.sphere_nu = Some(0.25);
        let back: Materials = serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
        assert_eq!(back, m);
        let old: Materials = serde_json::from_str(r#"{"sphere":"glass","plate":"steel"}"#).unwrap();
        assert_eq!(old.sphere_nu, None, "a file from before the parameter reads as the material's own ν");
    }

    #[test]
    fn a_variant_outside_the_clearance_is_refused() {
        let mut d = Design::default();
        d.damper.ball_position_m = 0.015;
        let v = d.check().unwrap();
        assert!(v.variant(0.05, 0.04).is_ok());
        assert_eq!(v.variant(0.05, 0.02).unwrap_err().param(), "ball-position", "|y0| 1.5 cm ≥ 1 cm");
        let e = sweep(&v, &[0.05], &[0.04, 0.02], None, &|_, _| {}).unwrap_err();
        assert_eq!(e.param(), "ball-position", "the sweep's cell at d 2 cm");
    }

    #[test]
    fn a_checked_design_is_read_back_only_if_it_checks() {
        let v = Design::default().check().unwrap();
        let text = serde_json::to_string(&v).unwrap();
        assert_eq!(text, serde_json::to_string(v.design()).unwrap(), "written as the design it holds");
        let back: ValidDesign = serde_json::from_str(&text).unwrap();
        assert_eq!(back, v);
        let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
        json["damper"]["main_mass_kg"] = serde_json::json!(1e7);
        let raw: Design = serde_json::from_value(json.clone()).unwrap();
        assert_eq!(raw.damper.main_mass_kg, 1e7, "a plain Design reads it");
        let e = serde_json::from_value::<ValidDesign>(json).unwrap_err().to_string();
        assert!(e.contains("invalid main-mass: ") && e.contains("out of range"), "{e}");
    }

    #[test]
    fn design_round_trips_through_json() {
        let d = Design::default();
        let back: Design = serde_json::from_str(&serde_json::to_string(&d).unwrap()).unwrap();
        assert_eq!(back, d);
    }

    /// One spelling written (units in the keys, enums as the flags spell them); thud 0.1's
    /// spelling still read, so saved designs and presets load (issue 26, item 5).
    #[test]
    fn design_is_written_in_the_one_spelling_and_read_in_the_old_one_too() {
        let mut d = Design::default();
        d.radiation.pulse = crate::acoustics::PulseShape::HalfSine;
        let text = serde_json::to_string(&d).unwrap();
        for new in ["\"k_hz_n_m1_5\":", "\"density_kg_m3\":", "\"solver\":\"event\"", "\"pulse\":\"half-sine\""] {
            assert!(text.contains(new), "{new} not in {text}");
        }
        let old = text
            .replace("\"k_hz_n_m1_5\":", "\"k_hz\":")
            .replace("\"density_kg_m3\":", "\"density\":")
            .replace("\"solver\":\"event\"", "\"solver\":\"Event\"")
            .replace("\"pulse\":\"half-sine\"", "\"pulse\":\"half_sine\"");
        assert_ne!(old, text);
        assert_eq!(serde_json::from_str::<Design>(&old).unwrap(), d);
        d.solver = crate::damper::Solver::newmark_default();
        d.ball = BallSize::Radius(0.01);
        let text = serde_json::to_string(&d).unwrap();
        assert!(text.contains("{\"newmark\":{\"dt_s\":") && text.contains("{\"radius_m\":0.01}"), "{text}");
        let old = text.replace("\"newmark\"", "\"Newmark\"").replace("\"radius_m\"", "\"radius\"");
        assert_eq!(serde_json::from_str::<Design>(&old).unwrap(), d);
    }
}
