//! The design's data: the damper, the ball's size and materials, the air, the listener, the
//! solver and the conventions for the reported numbers, with the paper's set-ups.

use serde::{Deserialize, Serialize};

use crate::acoustics::{Field, Observer, PulseShape, QuadSigns, Radiation, Source};
use crate::contact::{self, Impact, Target};
use crate::damper::{DamperParams, Solver};
use crate::error::{check_positive, ThudError};

/// How the impact mass's radius is found (it sets the sound, Eq 15, and K_HZ from materials).
/// Read as a table of its two keys, so that any other key is refused by its name.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", try_from = "BallSizeKeys")]
pub enum BallSize {
    /// From the mass and this density (kg/m³): a = (3m/(4πρ))^(1/3). Written `density_kg_m3`,
    /// read also as `density` (thud 0.1's spelling).
    #[serde(rename = "density_kg_m3", alias = "density")]
    Density(f64),
    /// A fixed radius (m), whatever the mass. Written `radius_m`, read also as `radius`.
    #[serde(rename = "radius_m", alias = "radius")]
    Radius(f64),
}

/// The keys a ball's table may hold: exactly one of them is given.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BallSizeKeys {
    #[serde(alias = "density")]
    density_kg_m3: Option<f64>,
    #[serde(alias = "radius")]
    radius_m: Option<f64>,
}

/// A ball's table with neither or both of its keys.
#[derive(Debug, thiserror::Error)]
#[error("a ball is given by one of `density_kg_m3` or `radius_m`")]
pub struct BallKeysError;

impl TryFrom<BallSizeKeys> for BallSize {
    type Error = BallKeysError;

    fn try_from(k: BallSizeKeys) -> Result<Self, BallKeysError> {
        match (k.density_kg_m3, k.radius_m) {
            (Some(rho), None) => Ok(BallSize::Density(rho)),
            (None, Some(a)) => Ok(BallSize::Radius(a)),
            _ => Err(BallKeysError),
        }
    }
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
#[serde(deny_unknown_fields)]
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
#[serde(deny_unknown_fields)]
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

    /// The air of this state, as the physical model hears through it
    /// ([`crate::acoustics::Air::from_state`]).
    #[must_use]
    pub fn air(&self) -> crate::acoustics::Air {
        crate::acoustics::Air::from_state(self.temperature_c, self.pressure_pa)
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
#[serde(deny_unknown_fields)]
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
#[serde(deny_unknown_fields)]
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
            Model::Physical => Radiation { pulse: PulseShape::Hertz, air: self.atmosphere.air(), ..self.radiation },
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
