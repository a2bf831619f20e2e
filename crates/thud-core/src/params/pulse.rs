//! The single impact ([`PulseInput`]) built from the rows of the one table that apply to an
//! impact ([`PULSE`]), read from the same draft as a design ([`DesignDraft`]).

use super::{base_ball_of, physical_conflicts, resolve_ball, BallGiven, DesignDraft, Given, Input, Spelling, PULSE};
use crate::acoustics::{Air, Field, Observer, PulseShape, QuadSigns, Radiation, Source};
use crate::contact::{self, Contact, Impact, Material, Target};
use crate::design::{BallSize, Design, Model};
use crate::error::ThudError;
use crate::limits::{self, short};

/// `a == b`, at compile time (a row looked up by its name in a `const` table).
pub const fn same_name(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// Everything one impact's sound needs, in SI units, and which parameters were given (to
/// name the right one when the field cannot be built).
#[derive(Debug, Clone)]
pub struct PulseInput {
    pub radius_m: f64,
    pub impact: Impact,
    pub observer: Observer,
    pub radiation: Radiation,
    /// The model the impact is heard through: its headline level ([`PulseInput::level_db`]).
    pub model: Model,
    /// (`radius` given, `mass` given, `r` given, spelling) for [`PulseInput::field`]'s errors.
    typed: (bool, bool, bool, Spelling),
}

/// One impact from named parameters. Defaults are the paper's Fig 2 impact (an acrylic sphere,
/// a 19.05 mm, m 40.5 g, U0 1.4 m/s, K_HZ 5.6e8 N/m^1.5, on a fixed plate, heard as a dipole at
/// r 0.7 m, θ 45°), or taken from `base` (a preset: its ball, K_HZ, observer, source and air,
/// and U0 = its v0; the target stays a fixed plate). The ball is resolved as a design's is
/// (the one rule, `resolve_ball`); with the physical model (`model`, or the base's) the
/// material is the sphere's or the paper's acrylic, K_HZ follows from Eq 2, the pulse is the
/// exact Hertz pulse and the air follows from its temperature and pressure.
pub fn pulse(base: Option<&Design>, given: &[(String, Input)], spelling: Spelling) -> Result<PulseInput, ThudError> {
    let given = Given::new(PULSE, given, spelling)?;
    given.relations()?;
    let start = base.cloned().unwrap_or_else(fig2_impact);
    // The base's ball as the base fixes it (a preset's as a design's: its mass and density, or
    // its radius); without a base, Fig 2's ball of fixed radius 19.05 mm.
    let base_ball = base_ball_of(&start.ball, start.damper.impact_mass_kg);
    let mut draft = DesignDraft::of(start);
    given.apply(&mut draft)?;
    let d = &draft.design;
    let model = d.model;
    physical_conflicts(&given, model)?;
    let physical = model == Model::Physical;
    let (sphere, plate) = materials(&draft, base, physical, &given)?;
    let ball = BallGiven {
        mass_kg: given.has("mass").then_some(d.damper.impact_mass_kg),
        radius_m: draft.radius_m,
        density_kg_m3: draft.density_kg_m3,
        material: sphere.as_ref().map(|s| (s.name, s.density_kg_m3)),
    };
    let (mass_kg, size) = resolve_ball(base_ball, &ball, |n| given.spell(n))?;
    let radius_m = match size {
        BallSize::Radius(r) => r,
        BallSize::Density(rho) => contact::sphere_radius(mass_kg, rho),
    };
    let ball_name = if given.has("radius") || !given.has("mass") { "radius" } else { "mass" };
    if !limits::RADIUS.contains(radius_m) {
        let rho = match size {
            BallSize::Density(rho) => rho,
            BallSize::Radius(_) => f64::NAN,
        };
        return Err(ThudError::invalid(
            given.spell(ball_name),
            format!(
                "{} kg at {} kg/m^3 makes a ball of radius {} m; the {} must be {}",
                short(mass_kg),
                short(rho),
                short(radius_m),
                limits::RADIUS.what,
                limits::RADIUS.describe()
            ),
        ));
    }
    limits::MASS.check_as(&given.spell("mass"), mass_kg)?;
    let k_hz = match (given.has("k-hz"), sphere, plate) {
        (true, _, _) => d.damper.k_hz,
        (false, Some(s), Some(p)) => contact::hertz_stiffness(radius_m, &s, &p),
        (false, None, Some(p)) => contact::hertz_stiffness(radius_m, &contact::material("acrylic")?, &p),
        // The base's materials, else its K_HZ (Fig 2's without a base).
        _ => match base.and_then(|b| b.materials.as_ref()) {
            Some(m) => m.hertz_stiffness(radius_m)?,
            None => d.damper.k_hz,
        },
    };
    limits::K_HZ.check_as(&given.spell(ball_name), k_hz)?;
    // The target stays a fixed plate unless a main mass is given (a base's is the structure's).
    let target = if given.has("main-mass") { Target::MovableMass(d.damper.main_mass_kg) } else { Target::FixedPlate };
    let u0 = d.damper.v0_m_s;
    limits::U0.check_as(&given.spell("u0"), u0)?;
    let impact = Impact { mass_kg, u0_m_s: u0, k_hz, target };
    impact.validate().map_err(|e| given.respell(e))?;
    // Heard as the drafted design is (its model's air and pulse); a base's angle not typed is
    // read back through degrees, as a typed angle is.
    let observer = match base {
        Some(_) if !given.has("theta") => Observer::new(d.observer.r_m, d.observer.theta_rad.to_degrees()),
        _ => d.observer,
    };
    let radiation = d.sound();
    Ok(PulseInput {
        radius_m,
        impact,
        observer,
        radiation,
        model,
        typed: (given.has("radius"), given.has("mass"), given.has("r"), spelling),
    })
}

/// The design an impact starts from without a base: Fig 2's impact (an acrylic ball, a
/// 19.05 mm, m 40.5 g, U0 1.4 m/s as the main mass's start, K_HZ 5.6e8 N/m^1.5, heard as a
/// dipole at r 0.7 m, θ 45° through the paper's air and half-sine pulse).
fn fig2_impact() -> Design {
    let mut d = Design {
        ball: BallSize::Radius(0.01905),
        materials: None,
        observer: Observer::new(0.7, 45.0),
        radiation: Radiation {
            source: Source::Dipole,
            quad_signs: QuadSigns::Rigid,
            air: Air::default(),
            pulse: PulseShape::default(),
        },
        ..Design::default()
    };
    d.damper.impact_mass_kg = 0.0405;
    d.damper.v0_m_s = 1.4;
    d.damper.k_hz = 5.6e8;
    d
}

/// The sphere's and the plate's materials of one impact: as named, else (physical model) the
/// base's or the paper's acrylic sphere; the plate is steel (or, physical, the base's) once a
/// sphere is known; none without a sphere or a plate.
fn materials(
    a: &DesignDraft,
    base: Option<&Design>,
    physical: bool,
    given: &Given<'_, DesignDraft>,
) -> Result<(Option<Material>, Option<Material>), ThudError> {
    let base_materials = base.and_then(Design::materials_used);
    let sphere = match (&a.sphere, &base_materials, physical) {
        (Some(s), _, _) => Some(contact::material(s).map_err(|e| given.respell(e.renamed("sphere")))?),
        (None, Some(m), true) => Some(m.sphere_material()?),
        (None, None, true) => Some(contact::material(crate::design::PHYSICAL_DEFAULT_SPHERE)?),
        (None, _, false) => None,
    };
    let plate = match (&a.plate, &sphere, &base_materials) {
        (Some(p), _, _) => Some(contact::material(p).map_err(|e| given.respell(e.renamed("plate")))?),
        (None, Some(_), Some(m)) if physical => Some(contact::material(&m.plate)?),
        (None, Some(_), _) => Some(contact::material("steel")?),
        (None, None, _) => None,
    };
    Ok((sphere, plate))
}

impl PulseInput {
    /// The headline level (dB re 20 µPa) of this impact's `field`: the paper's rms over τ, or
    /// the physical model's peak level ([`Design::level_db`]).
    pub fn level_db(&self, field: &Field) -> f64 {
        match self.model {
            Model::Paper => field.spl_db(),
            Model::Physical => field.peak_db(),
        }
    }

    /// The contact of the impact (Eqs 5–7).
    pub fn contact(&self) -> Contact {
        self.impact.contact()
    }

    /// The sound field of the impact at the observer (Eqs 9–24). An observer inside the ball is
    /// the ball's fault when the user sized the ball and left the observer alone: the error
    /// names the parameter they typed, not `r`.
    pub fn field(&self, contact: &Contact) -> Result<Field, ThudError> {
        let (radius, mass, r, spelling) = self.typed;
        Field::new(self.radius_m, contact, &self.observer, &self.radiation).map_err(|e| {
            let typed = [("radius", radius), ("mass", mass)].into_iter().find(|(_, t)| *t);
            match typed {
                Some((name, _)) if e.param() == "r" && !r => {
                    ThudError::invalid(spelling.spell(name), format!("the ball reaches the observer: {}", e.detail()))
                }
                _ if PULSE.iter().any(|p| p.name == e.param()) => {
                    let spelled = spelling.spell(e.param());
                    e.renamed(spelled)
                }
                _ => e,
            }
        })
    }
}
