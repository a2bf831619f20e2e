//! One impact's table [`PULSE`] and the impact it builds ([`PulseInput`]).

use super::{
    base_ball_of, model, physical_conflicts, pulse_shape, quad_signs, resolve_ball, source, Accepts, BallGiven,
    BaseBall, Conflict, Given, Group, Input, Param, Spelling, AIR_PRESSURE_HELP, AIR_TEMPERATURE_HELP, DESIGN, MODELS,
    MODEL_HELPS, PULSES, PULSE_HELPS, QUAD_SIGNS, SOURCES,
};
use crate::acoustics::{Air, Field, Observer, PulseShape, QuadSigns, Radiation, Source};
use crate::contact::{self, Contact, Impact, Material, Target};
use crate::design::{BallSize, Design, Model};
use crate::error::ThudError;
use crate::limits::{self, short, Range};
use crate::units::Kind;

/// A single impact being built from named parameters (`thud pulse`, Python's `pulse`).
#[derive(Debug, Clone, Default)]
pub struct PulseDraft {
    radius_m: Option<f64>,
    mass_kg: Option<f64>,
    density_kg_m3: Option<f64>,
    u0_m_s: Option<f64>,
    k_hz: Option<f64>,
    sphere: Option<String>,
    plate: Option<String>,
    main_mass_kg: Option<f64>,
    r_m: Option<f64>,
    theta_deg: Option<f64>,
    source: Option<Source>,
    quad_signs: Option<QuadSigns>,
    pulse: Option<PulseShape>,
    rho_c_pa_s_m: Option<f64>,
    c_m_s: Option<f64>,
    model: Option<Model>,
    temperature_c: Option<f64>,
    pressure_pa: Option<f64>,
}

/// The row of [`DESIGN`] called `name`'s range (every shared row of [`PULSE`] takes its range
/// from there, so a range is keyed by its row, never by a flag's name).
const fn design_range(name: &str) -> &'static Range {
    let mut i = 0;
    while i < DESIGN.len() {
        if let Accepts::Quantity { range, .. } = DESIGN[i].accepts {
            if same_name(DESIGN[i].name, name) {
                return range;
            }
        }
        i += 1;
    }
    panic!("no quantity row of that name in DESIGN")
}

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

/// A quantity row of [`PULSE`]: its placeholder and help (one argument per column of the
/// table, so each row reads as one line of it).
const fn pq(
    name: &'static str,
    kind: Kind,
    range: &'static Range,
    value_name: &'static str,
    help: &'static str,
    set: fn(&mut PulseDraft, f64),
) -> Param<PulseDraft> {
    Param::new(name, Group::Design, Accepts::Quantity { kind, range, set }, help).value(value_name)
}

/// A choice row of [`PULSE`].
const fn pch(
    name: &'static str,
    names: &'static [&'static str],
    helps: &'static [&'static str],
    type_name: &'static str,
    help: &'static str,
    set: fn(&mut PulseDraft, usize),
) -> Param<PulseDraft> {
    Param::new(name, Group::Listener, Accepts::Choice { names, helps, type_name, set }, help)
}

/// A row of [`PULSE`] that takes a material's name.
const fn pname(name: &'static str, help: &'static str, set: fn(&mut PulseDraft, &str)) -> Param<PulseDraft> {
    Param::new(name, Group::Design, Accepts::Name { set }, help).value("MATERIAL")
}

/// The parameters of one impact (`thud pulse`'s flags, Python's `pulse` keywords), in the
/// order they are checked and listed. The rows it shares with a design ([`DESIGN`]) take their
/// range from there (a range is keyed by its row, `design_range`); its helps are an impact's
/// (its defaults are Fig 2's, not a design's). Its own rows are the impact speed, K_HZ as a
/// number and the air's impedance and speed of sound (`sound-speed`, never `c`, which is the
/// structure's damping in a design).
#[rustfmt::skip]
pub const PULSE: &[Param<PulseDraft>] = &[
    pname("sphere", "Sphere material (steel, stainless-steel, acrylic, brass, aluminium, glass, rubber, nylon, tungsten-carbide)",
        |d, s| d.sphere = Some(s.to_string())),
    pname("plate", "Plate material [default: steel when --sphere is given]", |d, s| d.plate = Some(s.to_string())),
    pq("radius", Kind::Length, design_range("radius"), "A",
        "Sphere radius (m, or e.g. 19.05mm). Default: from --mass and --sphere's density, else 19.05 mm",
        |d, v| d.radius_m = Some(v)),
    pq("mass", Kind::Mass, design_range("mass"), "M",
        "Sphere mass (kg, or e.g. 40.5g). Default: from --radius and --sphere's density, else 40.5 g",
        |d, v| d.mass_kg = Some(v)),
    pq("density", Kind::Density, design_range("density"), "RHO",
        "Sphere density (kg/m³) [default: --sphere's]: with --mass the radius follows, with --radius the mass",
        |d, v| d.density_kg_m3 = Some(v)),
    Param {
        conflicts: Some(Conflict { with: &["sphere", "plate"], why: "K_HZ follows from the materials", names_other: false }),
        ..pq("k-hz", Kind::HertzStiffness, design_range("k-hz"), "KH",
            "Hertz stiffness K_HZ (N/m^1.5) [default: 5.6e8, or from --sphere/--plate]", |d, v| d.k_hz = Some(v))
    },
    pq("main-mass", Kind::Mass, design_range("main-mass"), "MM",
        "Mass of a movable target (kg): K* = (m+M)/(mM) (Eq 8). Default: a fixed plate",
        |d, v| d.main_mass_kg = Some(v)),
    pq("u0", Kind::Speed, &limits::U0, "U", "Impact speed U0 (m/s) [default: 1.4]", |d, v| d.u0_m_s = Some(v)),
    pq("rho-c", Kind::Impedance, &limits::RHO_C, "Z", "Air impedance ρ0·c (Pa·s/m) [default: 400, the paper's]",
        |d, v| d.rho_c_pa_s_m = Some(v)),
    pq("sound-speed", Kind::Speed, &limits::C_SOUND, "C", "Speed of sound (m/s) [default: 343]",
        |d, v| d.c_m_s = Some(v)),
    pq("r", Kind::Length, design_range("r"), "R", "Observer distance from the contact point (m) [default: 0.7]",
        |d, v| d.r_m = Some(v)),
    pq("theta", Kind::Angle, design_range("theta"), "DEG", "Observer angle from the plate's normal (degrees) [default: 45]",
        |d, v| d.theta_deg = Some(v)),
    pch("source", &SOURCES, &[], "Source",
        "Reflecting surfaces: a free sphere, a plate, or a wall–floor corner [default: dipole]",
        |d, i| d.source = Some(source(i))),
    pch("quad-signs", &QUAD_SIGNS, &[], "QuadSigns",
        "Quadrupole wall-image signs: the paper's (pressure-release wall) or a rigid wall [default: rigid]",
        |d, i| d.quad_signs = Some(quad_signs(i))),
    pch("pulse", &PULSES, &PULSE_HELPS, "PulseShape",
        "Acceleration pulse: the paper's half-sine (Eq 7) or the exact Hertz pulse [default: half-sine]",
        |d, i| d.pulse = Some(pulse_shape(i))),
    pch("model", &MODELS, &MODEL_HELPS, "Model",
        "The model of the world [default: paper]: physical is the measured level (peak, exact Hertz pulse, air from --air-temperature and --air-pressure, K_HZ and mass from the materials)",
        |d, i| d.model = Some(model(i))),
    pq("air-temperature", Kind::Temperature, design_range("air-temperature"), "T", AIR_TEMPERATURE_HELP,
        |d, v| d.temperature_c = Some(v)),
    pq("air-pressure", Kind::Pressure, design_range("air-pressure"), "P", AIR_PRESSURE_HELP,
        |d, v| d.pressure_pa = Some(v)),
];

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
    let mut a = PulseDraft::default();
    given.apply(&mut a)?;
    let model = a.model.or(base.map(|d| d.model)).unwrap_or_default();
    physical_conflicts(&given, model)?;
    let physical = model == Model::Physical;
    let (sphere, plate) = materials(&a, base, physical, &given)?;
    // The base's ball as the base fixes it (a preset's as a design's: its mass and density, or
    // its radius); without a base, Fig 2's ball of fixed radius 19.05 mm.
    let base_ball = base.map_or(BaseBall { mass_kg: 0.0405, size: BallSize::Radius(0.01905) }, |d| {
        base_ball_of(&d.ball, d.damper.impact_mass_kg)
    });
    let ball = BallGiven {
        mass_kg: a.mass_kg,
        radius_m: a.radius_m,
        density_kg_m3: a.density_kg_m3,
        material: sphere.map(|s| (s.name, s.density_kg_m3)),
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
    let k_hz = match (a.k_hz, sphere, plate) {
        (Some(k), _, _) => k,
        (None, Some(s), Some(p)) => contact::hertz_stiffness(radius_m, &s, &p),
        (None, None, Some(p)) => contact::hertz_stiffness(radius_m, &contact::material("acrylic")?, &p),
        _ => match base.as_ref().map(|d| (&d.materials, d.damper.k_hz)) {
            Some((Some(m), _)) => m.hertz_stiffness(radius_m)?,
            Some((None, k)) => k,
            None => 5.6e8,
        },
    };
    limits::K_HZ.check_as(&given.spell(ball_name), k_hz)?;
    let target = a.main_mass_kg.map_or(Target::FixedPlate, Target::MovableMass);
    let u0 = a.u0_m_s.or(base.as_ref().map(|d| d.damper.v0_m_s)).unwrap_or(1.4);
    limits::U0.check_as(&given.spell("u0"), u0)?;
    let impact = Impact { mass_kg, u0_m_s: u0, k_hz, target };
    impact.validate().map_err(|e| given.respell(e))?;
    let (observer, radiation) = heard(&a, base, physical);
    Ok(PulseInput {
        radius_m,
        impact,
        observer,
        radiation,
        model,
        typed: (given.has("radius"), given.has("mass"), given.has("r"), spelling),
    })
}

/// The sphere's and the plate's materials of one impact: as named, else (physical model) the
/// base's or the paper's acrylic sphere; the plate is steel (or, physical, the base's) once a
/// sphere is known; none without a sphere or a plate.
fn materials(
    a: &PulseDraft,
    base: Option<&Design>,
    physical: bool,
    given: &Given<'_, PulseDraft>,
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

/// Where and how one impact is heard: the observer and the radiation the draft `a` gives, else
/// the base's, else Fig 2's (a dipole at r 0.7 m, θ 45°, the paper's air and half-sine pulse);
/// with the physical model the air follows from its temperature and pressure and the pulse is
/// the exact Hertz pulse.
fn heard(a: &PulseDraft, base: Option<&Design>, physical: bool) -> (Observer, Radiation) {
    let base_air = base.as_ref().map_or(Air::default(), |d| d.radiation.air);
    let atmosphere = base.map(|d| d.atmosphere).unwrap_or_default();
    let air = if physical {
        Air::from_state(
            a.temperature_c.unwrap_or(atmosphere.temperature_c),
            a.pressure_pa.unwrap_or(atmosphere.pressure_pa),
        )
    } else {
        Air { rho_c_pa_s_m: a.rho_c_pa_s_m.unwrap_or(base_air.rho_c_pa_s_m), c_m_s: a.c_m_s.unwrap_or(base_air.c_m_s) }
    };
    let base_observer = base.as_ref().map_or(Observer::new(0.7, 45.0), |d| d.observer);
    let observer =
        Observer::new(a.r_m.unwrap_or(base_observer.r_m), a.theta_deg.unwrap_or(base_observer.theta_rad.to_degrees()));
    let source = a.source.or(base.as_ref().map(|d| d.radiation.source)).unwrap_or(Source::Dipole);
    let quad_signs = a.quad_signs.or(base.as_ref().map(|d| d.radiation.quad_signs)).unwrap_or(QuadSigns::Rigid);
    let pulse = if physical {
        PulseShape::Hertz
    } else {
        a.pulse.or(base.as_ref().map(|d| d.radiation.pulse)).unwrap_or_default()
    };
    (observer, Radiation { source, quad_signs, air, pulse })
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
