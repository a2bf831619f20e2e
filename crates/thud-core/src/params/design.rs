//! The design's table [`DESIGN`] and what builds, checks and documents a design from it.

use super::{
    base_ball_of, edit_distance, model, physical_conflicts, pulse_shape, quad_signs, resolve_ball, source, Accepts,
    BallGiven, Conflict, Given, Group, ImpactSide, Input, Param, Spelling, AIR_PRESSURE_HELP, AIR_TEMPERATURE_HELP,
    MODELS, MODEL_HELPS, PULSES, PULSE_HELPS, QUAD_SIGNS, SOLVERS, SOLVER_HELPS, SOURCES,
};
use crate::acoustics::{PulseShape, QuadSigns, Source};
use crate::damper::Solver;
use crate::design::{BallSize, Design, Materials, Model, ValidDesign};
use crate::error::ThudError;
use crate::limits::{self, short, Range};
use crate::units::Kind;

/// A design, or a single impact, being built from a base design and named parameters: the
/// one draft every row of [`PARAMS`] writes to.
#[derive(Debug, Clone)]
pub struct DesignDraft {
    pub design: Design,
    /// `solver`, as an index into [`SOLVERS`].
    solver: Option<usize>,
    dt_s: Option<f64>,
    pub(super) sphere: Option<String>,
    pub(super) plate: Option<String>,
    /// The ball's Poisson ratio ν, for the materials `sphere` names.
    sphere_nu: Option<f64>,
    /// The ball's radius (m) and density (kg/m³) as given, for [`resolve_ball`].
    pub(super) radius_m: Option<f64>,
    pub(super) density_kg_m3: Option<f64>,
}

impl DesignDraft {
    /// A draft of `design` with nothing given yet.
    pub(super) fn of(design: Design) -> Self {
        DesignDraft {
            design,
            solver: None,
            dt_s: None,
            sphere: None,
            plate: None,
            sphere_nu: None,
            radius_m: None,
            density_kg_m3: None,
        }
    }
}

/// A row of [`DESIGN`]: a quantity with its help, placeholder, group and accessor (one
/// argument per column of the table, so each row reads as one line of it).
#[allow(clippy::too_many_arguments)]
const fn q(
    name: &'static str,
    kind: Kind,
    range: &'static Range,
    group: Group,
    value_name: &'static str,
    help: &'static str,
    get: fn(&Design) -> f64,
    set: fn(&mut DesignDraft, f64),
) -> Param<DesignDraft> {
    Param::new(name, group, Accepts::Quantity { kind, range, set }, help).value(value_name).get(get)
}

/// A choice row of [`DESIGN`].
const fn ch(
    name: &'static str,
    group: Group,
    names: &'static [&'static str],
    helps: &'static [&'static str],
    type_name: &'static str,
    help: &'static str,
    set: fn(&mut DesignDraft, usize),
) -> Param<DesignDraft> {
    Param::new(name, group, Accepts::Choice { names, helps, type_name, set }, help)
}

/// A switch row of [`DESIGN`].
const fn sw(
    name: &'static str,
    group: Group,
    help: &'static str,
    get: fn(&Design) -> f64,
    set: fn(&mut DesignDraft, bool),
) -> Param<DesignDraft> {
    Param::new(name, group, Accepts::Switch { set }, help).get(get)
}

/// Every named parameter, in the order they are checked and listed: a design's (`simulate`,
/// `sweep`, `export`, `response`; Python's `simulate`, `sweep`, `response`; the explorer's
/// fields; the config file) and a single impact's (`thud pulse`, Python's `pulse`), each row
/// saying where it applies ([`Where`](super::Where); the views [`DESIGN`] and [`PULSE`]). Each row is the
/// one definition of its parameter: the command line's flag (and its help, completion and man
/// page), Python's keyword (and its stub), the explorer's field, its range
/// ([`crate::limits`]) and where its value goes in the one draft ([`DesignDraft`]), which the
/// design and the impact builders both read.
#[rustfmt::skip]
pub const PARAMS: &[Param<DesignDraft>] = &[
    q("mass", Kind::Mass, &limits::MASS, Group::Design, "M", "Impact mass m (kg, or e.g. 40.5g)",
        |d| d.damper.impact_mass_kg, |d, v| d.design.damper.impact_mass_kg = v)
        .both("Sphere mass (kg, or e.g. 40.5g). Default: from --radius and --sphere's density, else 40.5 g"),
    q("gap", Kind::Length, &limits::GAP, Group::Design, "D", "Total clearance d (m, or e.g. 4cm)",
        |d| d.damper.gap_m, |d, v| d.design.damper.gap_m = v),
    q("v0", Kind::Speed, &limits::V0, Group::Forcing, "V", "Initial velocity of the main mass (m/s)",
        |d| d.damper.v0_m_s, |d, v| d.design.damper.v0_m_s = v),
    // An impact's speed is where a design's main mass starts (a preset's U0 is its v0).
    Param::new("u0", Group::Forcing, Accepts::Quantity { kind: Kind::Speed, range: &limits::U0,
        set: |d: &mut DesignDraft, v| d.design.damper.v0_m_s = v }, "Impact speed U0 (m/s) [default: 1.4]")
        .value("U").impact_only(),
    q("main-mass", Kind::Mass, &limits::MAIN_MASS, Group::Design, "MM", "Main mass M (kg)",
        |d| d.damper.main_mass_kg, |d, v| d.design.damper.main_mass_kg = v)
        .both("Mass of a movable target (kg): K* = (m+M)/(mM) (Eq 8). Default: a fixed plate"),
    q("k", Kind::Stiffness, &limits::STIFFNESS, Group::Design, "K", "Spring stiffness K (N/m)",
        |d| d.damper.stiffness_n_m, |d, v| d.design.damper.stiffness_n_m = v),
    q("c", Kind::Damping, &limits::DAMPING, Group::Design, "C", "Viscous damping C (N·s/m)",
        |d| d.damper.damping_n_s_m, |d, v| d.design.damper.damping_n_s_m = v),
    q("c1", Kind::Damping, &limits::C1, Group::Design, "C1", "Contact damping c1 (N·s/m)",
        |d| d.damper.c1_n_s_m, |d, v| d.design.damper.c1_n_s_m = v),
    Param {
        conflicts: Some(Conflict { with: &["sphere"], why: "K_HZ follows from the materials", names_other: false }),
        impact: ImpactSide {
            help: "Hertz stiffness K_HZ (N/m^1.5) [default: 5.6e8, or from --sphere/--plate]",
            conflicts: Some(Conflict { with: &["sphere", "plate"], why: "K_HZ follows from the materials", names_other: false }),
            requires: None,
        },
        ..q("k-hz", Kind::HertzStiffness, &limits::K_HZ, Group::Design, "KH", "Hertz stiffness K_HZ (N/m^1.5)",
            |d| d.damper.k_hz, |d, v| d.design.damper.k_hz = v).applies(|d| d.materials_used().is_none()).both("")
            .only_in(Model::Paper, "the physical model takes K_HZ from the materials (Eq 2)")
    },
    Param::new("sphere", Group::Design, Accepts::Name { set: |d: &mut DesignDraft, s| d.sphere = Some(s.to_string()) },
        "Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)").value("MATERIAL")
        .both("Sphere material (steel, stainless-steel, acrylic, brass, aluminium, glass, rubber, nylon, tungsten-carbide)"),
    // An impact takes a plate alone (on the paper's acrylic sphere); a design's plate needs its ball's material.
    Param {
        requires: Some("sphere"),
        ..Param::new("plate", Group::Design, Accepts::Name { set: |d: &mut DesignDraft, s| d.plate = Some(s.to_string()) },
            "Enclosure material (with --sphere) [default: steel]").value("MATERIAL")
            .both("Plate material [default: steel when --sphere is given]")
    },
    // A design without materials has no ball ν: NaN, which a front end shows as not applicable.
    Param {
        requires: Some("sphere"),
        ..q("sphere-poisson", Kind::Number, &limits::SPHERE_POISSON, Group::Design, "NU",
            "The ball's Poisson ratio ν in K_HZ (Eq 2), instead of its material's (with --sphere)",
            |d| d.materials.as_ref().and_then(|m| m.sphere_nu.or_else(|| Some(m.sphere_material().ok()?.nu))).unwrap_or(f64::NAN),
            |d, v| {
                d.sphere_nu = Some(v);
                if let Some(m) = d.design.materials.as_mut() {
                    m.sphere_nu = Some(v);
                }
            }).label("ball ν").applies(|d| d.materials.as_ref().is_some_and(|m| m.sphere_nu.is_some()))
    },
    sw("no-tension", Group::Design, "Clamp the contact force at ≥ 0 (a contact cannot pull)",
        |d| f64::from(u8::from(d.damper.no_tension)), |d, on| d.design.damper.no_tension = on),
    q("duration", Kind::Time, &limits::DURATION, Group::Solver, "T", "Simulated time (s)",
        |d| d.damper.duration_s, |d, v| d.design.damper.duration_s = v),
    ch("solver", Group::Solver, &SOLVERS, &SOLVER_HELPS, "Solver", "Solver", |d, i| d.solver = Some(i)),
    q("dt", Kind::Time, &limits::DT, Group::Solver, "DT", "Newmark time step (s) [default: 1e-7]",
        |d| match d.solver { Solver::Newmark { dt_s } => dt_s, Solver::Event => NEWMARK_DT_S }, |d, v| d.dt_s = Some(v))
        .applies(|d| matches!(d.solver, Solver::Newmark { .. })),
    q("density", Kind::Density, &limits::DENSITY, Group::Design, "RHO",
        "Ball density (kg/m³) [default: the --sphere material's]: with --mass the radius follows, with --radius the mass",
        |d| match d.ball { BallSize::Density(rho) => rho, BallSize::Radius(_) => f64::NAN },
        |d, v| { d.design.ball = BallSize::Density(v); d.density_kg_m3 = Some(v); }).label("ball ρ")
        .applies(|d| matches!(d.ball, BallSize::Density(_)))
        .both("Sphere density (kg/m³) [default: --sphere's]: with --mass the radius follows, with --radius the mass"),
    q("radius", Kind::Length, &limits::RADIUS, Group::Design, "A",
        "Ball radius (m): with --mass as given, else the mass follows from the density",
        Design::ball_radius_m, |d, v| { d.design.ball = BallSize::Radius(v); d.radius_m = Some(v); }).label("ball a")
        .applies(|d| matches!(d.ball, BallSize::Radius(_)))
        .both("Sphere radius (m, or e.g. 19.05mm). Default: from --mass and --sphere's density, else 19.05 mm"),
    q("r", Kind::Length, &limits::R, Group::Listener, "R", "Observer distance (m)",
        |d| d.observer.r_m, |d, v| d.design.observer.r_m = v)
        .both("Observer distance from the contact point (m) [default: 0.7]"),
    q("theta", Kind::Angle, &limits::THETA, Group::Listener, "DEG", "Observer angle (degrees)",
        |d| d.observer.theta_rad.to_degrees(), |d, v| d.design.observer.theta_rad = v.to_radians())
        .both("Observer angle from the plate's normal (degrees) [default: 45]"),
    ch("source", Group::Listener, &SOURCES, &[], "Source", "Reflecting surfaces around the impact",
        |d, i| d.design.radiation.source = source(i))
        .get(|d| Source::ALL.iter().position(|s| *s == d.radiation.source).map_or(f64::NAN, |i| i as f64))
        .both("Reflecting surfaces: a free sphere, a plate, or a wall–floor corner [default: dipole]"),
    ch("quad-signs", Group::Listener, &QUAD_SIGNS, &[], "QuadSigns", "Quadrupole wall-image signs",
        |d, i| d.design.radiation.quad_signs = quad_signs(i))
        .get(|d| if d.radiation.quad_signs == QuadSigns::Paper { 0.0 } else { 1.0 })
        .both("Quadrupole wall-image signs: the paper's (pressure-release wall) or a rigid wall [default: rigid]"),
    ch("pulse", Group::Listener, &PULSES, &PULSE_HELPS, "PulseShape",
        "Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse",
        |d, i| d.design.radiation.pulse = pulse_shape(i))
        .get(|d| if d.radiation.pulse == PulseShape::HalfSine { 0.0 } else { 1.0 })
        .only_in(Model::Paper, "the physical model uses the exact Hertz pulse")
        .both("Acceleration pulse: the paper's half-sine (Eq 7) or the exact Hertz pulse [default: half-sine]"),
    Param {
        get: Some(|d| if d.model == Model::Physical { 1.0 } else { 0.0 }),
        ..ch("model", Group::Listener, &MODELS, &MODEL_HELPS, "Model",
            "The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)",
            |d, i| d.design.model = model(i))
            .both("The model of the world [default: paper]: physical is the measured level (peak, exact Hertz pulse, air from --air-temperature and --air-pressure, K_HZ and mass from the materials)")
    },
    q("air-temperature", Kind::Temperature, &limits::AIR_TEMPERATURE, Group::Listener, "T", AIR_TEMPERATURE_HELP,
        |d| d.atmosphere.temperature_c, |d, v| d.design.atmosphere.temperature_c = v).label("air T").both("")
        .only_in(Model::Physical, PAPER_AIR),
    q("air-pressure", Kind::Pressure, &limits::AIR_PRESSURE, Group::Listener, "P", AIR_PRESSURE_HELP,
        |d| d.atmosphere.pressure_pa, |d, v| d.design.atmosphere.pressure_pa = v).label("air p").both("")
        .only_in(Model::Physical, PAPER_AIR),
    // The paper model's air (`sound-speed`, never `c`, which is the structure's damping).
    q("rho-c", Kind::Impedance, &limits::RHO_C, Group::Listener, "Z",
        "Air impedance ρ0·c of the paper model (Pa·s/m) [default: 400, the paper's]",
        |d| d.radiation.air.rho_c_pa_s_m, |d, v| d.design.radiation.air.rho_c_pa_s_m = v)
        .label("air ρ0c").applies(|d| d.model == Model::Paper).both("")
        .only_in(Model::Paper, PHYSICAL_AIR),
    q("sound-speed", Kind::Speed, &limits::C_SOUND, Group::Listener, "C",
        "Speed of sound c of the paper model (m/s) [default: 343]",
        |d| d.radiation.air.c_m_s, |d, v| d.design.radiation.air.c_m_s = v)
        .label("air c").applies(|d| d.model == Model::Paper).both("")
        .only_in(Model::Paper, PHYSICAL_AIR),
    q("l-star", Kind::Level, &limits::L_STAR, Group::Study, "DB", "Zone threshold L* on SPLmax (dB)",
        |d| d.thresholds.spl_db, |d, v| d.design.thresholds.spl_db = v),
    q("e-star", Kind::Inclination, &limits::E_STAR, Group::Study, "CM_S", "Zone threshold e* on the damping inclination (cm/s)",
        |d| d.thresholds.inclination_cm_s, |d, v| d.design.thresholds.inclination_cm_s = v),
    // The harmonic force F0·cos(2πft) on the main mass and the ball's start (docs/model.md §6).
    Param {
        alias: Some("force-amplitude"),
        ..q("force", Kind::Force, &limits::FORCE, Group::Forcing, "F0",
            "Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq",
            |d| d.damper.force_n, |d, v| d.design.damper.force_n = v)
    },
    q("freq", Kind::Frequency, &limits::FREQ, Group::Forcing, "F", "Frequency f of the harmonic force (Hz, or e.g. 5Hz)",
        |d| d.damper.freq_hz, |d, v| d.design.damper.freq_hz = v).applies(|d| d.damper.freq_hz != 0.0),
    q("ball-position", Kind::Length, &limits::BALL_POSITION, Group::Forcing, "Y0",
        "The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred]",
        |d| d.damper.ball_position_m, |d, v| d.design.damper.ball_position_m = v),
    q("ball-velocity", Kind::Speed, &limits::BALL_VELOCITY, Group::Forcing, "W0", "The ball's initial velocity w0 (m/s) [default: 0]",
        |d| d.damper.ball_velocity_m_s, |d, v| d.design.damper.ball_velocity_m_s = v).label("ball w0"),
    Param::new("periods", Group::Solver, Accepts::Count {
            range: &limits::PERIODS,
            set: |d: &mut DesignDraft, n| d.design.damper.steady_periods = u32::try_from(n).unwrap_or(u32::MAX),
        }, "Forcing periods N of the steady-state window of a forced run [default: 10]")
        .value("N").label("periods N").get(|d| f64::from(d.damper.steady_periods)),
    sw("settle", Group::Solver, "Run a forced run on past --duration, N periods at a time, until its steady amplitude settles",
        |d| f64::from(u8::from(d.damper.settle)), |d, on| d.design.damper.settle = on),
];

/// Why the paper model refuses the air's state.
const PAPER_AIR: &str = "only the physical model takes the air from its temperature and pressure; the paper model's air is its rho-c and sound-speed";
/// Why the physical model refuses the paper's air.
const PHYSICAL_AIR: &str = "the physical model takes the air from its temperature and pressure";

/// How many rows of [`PARAMS`] reach a design (`impact` false) or an impact (`impact` true).
const fn count(impact: bool) -> usize {
    let (mut i, mut n) = (0, 0);
    while i < PARAMS.len() {
        if reaches(&PARAMS[i], impact) {
            n += 1;
        }
        i += 1;
    }
    n
}

const fn reaches(p: &Param<DesignDraft>, impact: bool) -> bool {
    if impact {
        p.used_in.impact()
    } else {
        p.used_in.design()
    }
}

/// The `N` rows of [`PARAMS`] that reach a design or an impact, in table order; an impact's as
/// it reads them ([`ImpactSide`]).
const fn view<const N: usize>(impact: bool) -> [Param<DesignDraft>; N] {
    let mut out = [PARAMS[0]; N];
    let (mut i, mut k) = (0, 0);
    while i < PARAMS.len() {
        if reaches(&PARAMS[i], impact) {
            out[k] = if impact { PARAMS[i].as_impact() } else { PARAMS[i] };
            k += 1;
        }
        i += 1;
    }
    out
}

const DESIGN_ROWS: usize = count(false);
const IMPACT_ROWS: usize = count(true);

/// The rows of [`PARAMS`] that apply to a design, in table order: every design command's
/// flags, Python's design keywords, the explorer's fields and the config file's keys.
pub const DESIGN: &[Param<DesignDraft>] = &view::<DESIGN_ROWS>(false);

/// The rows of [`PARAMS`] that apply to a single impact, in table order, each as an impact
/// reads it ([`ImpactSide`]): `thud pulse`'s flags and Python's `pulse` keywords.
pub const PULSE: &[Param<DesignDraft>] = &view::<IMPACT_ROWS>(true);

/// The Newmark step a design takes when the newmark solver is asked for without a step (s):
/// the paper's.
pub const NEWMARK_DT_S: f64 = 1e-7;

/// The row of [`DESIGN`] called `name` (its name as in the table, `main-mass`).
pub fn design_param(name: &str) -> Option<&'static Param<DesignDraft>> {
    DESIGN.iter().find(|p| p.name == name)
}

/// Checks every parameter of a design against its range: the value of every row of [`DESIGN`]
/// with a range, wherever the row applies (its `applies` column, [`Param`]; θ against the range
/// of the design's source, [`limits::theta_deg`]), then what the rows do not hold: a force's
/// frequency, the ball inside the clearance, the ball radius from mass and density, K_HZ from
/// the materials, and the air. The error names the parameter (bare, as on the command line).
/// Part of [`Design::check`]; derived from the table, so a row added to it is checked here.
pub fn check_design(d: &Design) -> Result<(), ThudError> {
    for p in DESIGN {
        let (Some(range), Some(get)) = (p.range(), p.get) else { continue };
        if p.applies.is_some_and(|applies| !applies(d)) {
            continue;
        }
        if *range == limits::THETA {
            // Degrees back from radians to 1e-9 deg, so 90° stays 90°.
            limits::theta_deg(d.radiation.source).check((get(d) * 1e9).round() / 1e9)?;
        } else {
            range.check(get(d))?;
        }
    }
    let p = &d.damper;
    if p.force_n > 0.0 && p.freq_hz == 0.0 {
        return Err(ThudError::invalid("freq", "a force needs a frequency; give --freq (Hz)"));
    }
    if p.ball_position_m.abs() >= 0.5 * p.gap_m {
        return Err(ThudError::invalid(
            "ball-position",
            format!(
                "{} m puts the ball outside the clearance; |y0| must be < d/2 = {} m",
                short(p.ball_position_m),
                short(0.5 * p.gap_m)
            ),
        ));
    }
    if let BallSize::Density(rho) = d.ball {
        let a = d.ball_radius_m();
        if !limits::RADIUS.contains(a) {
            return Err(ThudError::invalid(
                "mass",
                format!(
                    "{} kg at {} kg/m^3 makes a ball of radius {} m; the {} must be {}",
                    short(p.impact_mass_kg),
                    short(rho),
                    short(a),
                    limits::RADIUS.what,
                    limits::RADIUS.describe()
                ),
            ));
        }
    }
    if let Some(m) = &d.materials_used() {
        let k = m.hertz_stiffness(d.ball_radius_m())?;
        if !limits::K_HZ.contains(k) {
            return Err(ThudError::invalid(
                "radius",
                format!(
                    "{} m of {} on {} gives K_HZ {} N/m^1.5; the {} must be {}",
                    short(d.ball_radius_m()),
                    m.sphere,
                    m.plate,
                    short(k),
                    limits::K_HZ.what,
                    limits::K_HZ.describe()
                ),
            ));
        }
    }
    // The air of either model (the rows above check the paper model's as typed).
    limits::RHO_C.check(d.radiation.air.rho_c_pa_s_m)?;
    limits::C_SOUND.check_as("speed of sound", d.radiation.air.c_m_s)?;
    Ok(())
}

impl Design {
    /// Checks the whole design and resolves what follows from it: the only way to a
    /// [`ValidDesign`], the design every solver takes. In order: the physics' own checks
    /// ([`Design::validate`]: positive masses and gap, |y0| < d/2, the observer outside the
    /// ball and on the open side of the source's walls, finite thresholds), then every range of
    /// the parameter table and the derived quantities ([`check_design`]: the ball radius from
    /// mass and density, K_HZ from the materials), then K_HZ set from the materials for the
    /// ball's radius. The first problem is the error, naming the parameter bare (`mass`), as
    /// the command line spells it without dashes. (Here beside the parameter table, so that the
    /// design module, which the table's rows read and write, does not read the table.)
    pub fn check(self) -> Result<ValidDesign, ThudError> {
        self.validate()?;
        check_design(&self)?;
        ValidDesign::from_ranges_checked(self)
    }
}

impl TryFrom<Design> for ValidDesign {
    type Error = ThudError;

    fn try_from(d: Design) -> Result<Self, ThudError> {
        d.check()
    }
}

/// A checked design is read as a [`Design`] and then checked ([`Design::check`]): a file
/// cannot skip the check.
impl<'de> serde::Deserialize<'de> for ValidDesign {
    fn deserialize<D: serde::Deserializer<'de>>(de: D) -> Result<Self, D::Error> {
        Design::deserialize(de)?.check().map_err(serde::de::Error::custom)
    }
}

/// The keyword lines of Python's stub (`crates/thud-py/python/thud/__init__.pyi`) for the rows of [`DESIGN`]
/// not in `skip`, in table order, each with its help and range as a comment:
/// `    mass: Optional[Quantity] = None,  # Impact mass m (kg, or e.g. 40.5g); 0.0001 to 100 kg`.
/// A test keeps the checked-in stub equal to this.
pub fn stub_keywords(skip: &[&str]) -> String {
    stub_lines(DESIGN, skip)
}

/// The keyword lines of Python's `pulse` in its stub: the rows of [`PULSE`], as
/// [`stub_keywords`] writes a design's.
pub fn impact_stub_keywords() -> String {
    stub_lines(PULSE, &[])
}

fn stub_lines(table: &[Param<DesignDraft>], skip: &[&str]) -> String {
    let mut out = String::new();
    for p in table.iter().filter(|p| !skip.contains(&p.name)) {
        let ty = match p.accepts {
            Accepts::Quantity { .. } => "Quantity",
            Accepts::Count { .. } => "Count",
            Accepts::Switch { .. } => "bool",
            Accepts::Name { .. } => "str",
            Accepts::Choice { type_name, .. } => type_name,
        };
        let name = Spelling::Keyword.spell(p.name);
        out += &format!("    {name}: Optional[{ty}] = None,  # {}\n", p.doc_line(Spelling::Keyword));
    }
    out
}

/// `design` with the numeric row `p` of [`DESIGN`] set to `value` (internal units; a count is
/// rounded, a switch is on when `value` ≠ 0, a choice is the index of its name), unchecked:
/// the explorer's field for a row the panel shows as a number. Rows that set more than the
/// design (the solver, its step, the materials) leave it as it is.
pub fn set_number(design: &Design, p: &Param<DesignDraft>, value: f64) -> Design {
    let mut draft = DesignDraft::of(design.clone());
    match p.accepts {
        Accepts::Quantity { set, .. } => set(&mut draft, value),
        Accepts::Count { set, .. } => {
            set(&mut draft, if value.is_finite() && value >= 0.0 { value.round() as usize } else { 0 });
        }
        Accepts::Switch { set } => set(&mut draft, value != 0.0),
        // Only a choice that sets the design alone reads its index back (`get`): the source,
        // its signs, the pulse, the model.
        Accepts::Choice { set, names, .. } if p.get.is_some() => {
            if value.is_finite() && value >= 0.0 && value < names.len() as f64 {
                set(&mut draft, value as usize);
            }
        }
        Accepts::Choice { .. } | Accepts::Name { .. } => {}
    }
    draft.design
}

/// The design `base` with the named parameters `given` applied, checked: each value against its
/// range (the error names the parameter as `spelling` spells it), then the whole design and its
/// derived quantities (ball radius, K_HZ from materials, the observer outside the ball). The
/// result is a [`ValidDesign`] ([`Design::check`]): K_HZ resolved from its materials, if any,
/// and ready for the solvers.
pub fn design(base: Design, given: &[(String, Input)], spelling: Spelling) -> Result<ValidDesign, ThudError> {
    let given = Given::new(DESIGN, given, spelling)?;
    given.relations()?;
    let (base_ball, base_mass) = (base.ball, base.damper.impact_mass_kg);
    let mut draft = DesignDraft::of(base);
    given.apply(&mut draft)?;
    let DesignDraft { design: mut d, solver, dt_s, sphere, plate, sphere_nu, radius_m, density_kg_m3 } = draft;
    if let Some(sphere) = sphere {
        d.materials = Some(Materials { sphere, plate: plate.unwrap_or_else(|| "steel".into()), sphere_nu });
    }
    physical_conflicts(&given, d.model)?;
    // The ball's material density: the sphere's when one was named, and with the physical
    // model the material it assumes; none otherwise (the paper's ball, 40.5 g at 19.05 mm).
    let material = match (given.has("sphere"), d.model) {
        (true, _) | (false, Model::Physical) => {
            d.materials_used().map(|m| m.sphere_material()).transpose().map_err(|e| given.respell(e))?
        }
        (false, Model::Paper) => None,
    };
    let ball = BallGiven {
        mass_kg: given.has("mass").then_some(d.damper.impact_mass_kg),
        radius_m,
        density_kg_m3,
        material: material.map(|m| (m.name, m.density_kg_m3)),
    };
    let base_ball = base_ball_of(&base_ball, base_mass);
    let (mass, size) = resolve_ball(base_ball, &ball, |n| given.spell(n))?;
    d.damper.impact_mass_kg = mass;
    d.ball = size;
    d.solver = match (solver, dt_s, d.solver) {
        (Some(0), _, _) => Solver::Event,
        (Some(_), dt, _) => Solver::Newmark { dt_s: dt.unwrap_or(NEWMARK_DT_S) },
        (None, Some(dt), Solver::Newmark { .. }) => Solver::Newmark { dt_s: dt },
        (None, Some(_), Solver::Event) => {
            return Err(ThudError::invalid(
                given.spell("dt"),
                format!("only the newmark solver has a time step; add {}", solver_hint(spelling)),
            ))
        }
        (None, None, s) => s,
    };
    if d.damper.force_n > 0.0 && d.damper.freq_hz == 0.0 {
        let freq = given.spell("freq");
        return Err(ThudError::invalid(&freq, format!("a force needs a frequency; give {freq} (Hz)")));
    }
    check_design(&d).map_err(|e| given.respell(e))?;
    d.validate().map_err(|e| blame_ball(&given, e, &d))?;
    d.check().map_err(|e| given.respell(e))
}

/// The design of a frequency response (`thud response`, Python's `thud.response`): `base`
/// with the named parameters `given` applied as [`design`] does, at the first frequency
/// `first_hz` (each point of the response sets its own), and from rest (v0 = 0) unless the
/// start was given (`v0`, `ball-position`, `ball-velocity`). A frequency given is refused (the
/// response sweeps it), and so is a design without a force; `force` names the force's
/// parameter as this front end calls it when it was not given (`force`, `force-amplitude`).
pub fn response_design(
    mut base: Design,
    given: &[(String, Input)],
    spelling: Spelling,
    first_hz: f64,
    force: &str,
) -> Result<ValidDesign, ThudError> {
    let typed = |name: &str| given.iter().find(|(n, _)| *n == spelling.key(name)).map(|(_, v)| v);
    if let Some(v) = typed("freq") {
        let freqs = match spelling {
            Spelling::Flag => "--freqs FROM:TO:N",
            Spelling::Keyword => "the frequencies as freqs_hz",
        };
        return Err(ThudError::invalid(
            spelling.spell("freq"),
            format!("{}: a response sweeps the frequency; give {freqs}", v.shown()),
        ));
    }
    base.damper.freq_hz = first_hz;
    if ["v0", "ball-position", "ball-velocity"].iter().all(|n| typed(n).is_none()) {
        base.damper.v0_m_s = 0.0;
    }
    let d = design(base, given, spelling)?;
    if !d.damper.forced() {
        let force = spelling.spell(force);
        return Err(ThudError::invalid(&force, format!("0 N: a response needs a force; give {force} F0 (N)")));
    }
    Ok(d)
}

/// The design of a frequency response and its frequencies (Hz): `freqs_hz` when the front end
/// was given them, else the engine's default band of the design
/// ([`crate::response::default_freqs_hz`], 0.6–1.6 × the natural frequency). The design is
/// built first ([`response_design`]); its band depends on M, K and C only, which the named
/// parameters set before any frequency counts, so the band of the design as given starts the
/// design and is the band of the design built.
pub fn response_setup(
    base: Design,
    given: &[(String, Input)],
    spelling: Spelling,
    freqs_hz: Option<Vec<f64>>,
    force: &str,
) -> Result<(ValidDesign, Vec<f64>), ThudError> {
    if let Some(freqs) = freqs_hz {
        let first = freqs.first().copied().unwrap_or(0.0);
        return Ok((response_design(base, given, spelling, first, force)?, freqs));
    }
    // M, K and C as given (a value refused here is refused again, in order, by the design).
    // The band depends on M, K and C only, so the drafted design's band is the built one's.
    let drafted = drafted(base.clone(), given, spelling).unwrap_or_else(|_| base.clone());
    let freqs = crate::response::default_freqs_hz(&drafted);
    let d = response_design(base, given, spelling, freqs[0], force)?;
    debug_assert_eq!(freqs, crate::response::default_freqs_hz(&d), "the band follows M, K and C only");
    Ok((d, freqs))
}

/// Checks each of the named parameters `given` on its own: a known name (a row of [`DESIGN`]
/// or its alias, as `spelling` hands it in), given once, with a value its row accepts (inside
/// its range, a known choice). No relation between them and no whole-design check: what a
/// settings file can be checked for key by key.
pub fn check_named(given: &[(String, Input)], spelling: Spelling) -> Result<(), ThudError> {
    drafted(Design::default(), given, spelling).map(drop)
}

/// The row of [`DESIGN`] whose name (or alias) is nearest to `name` (edit distance; `_` read as
/// `-`): what "did you mean" names.
pub fn nearest_design_param(name: &str) -> Option<&'static str> {
    let canonical = name.replace('_', "-");
    DESIGN.iter().flat_map(|p| std::iter::once(p.name).chain(p.alias)).min_by_key(|n| edit_distance(&canonical, n))
}

/// `base` with the named parameters `given` set, each checked against its range only (no
/// relation, no whole-design check).
fn drafted(base: Design, given: &[(String, Input)], spelling: Spelling) -> Result<Design, ThudError> {
    let given = Given::new(DESIGN, given, spelling)?;
    let mut draft = DesignDraft::of(base);
    given.apply(&mut draft)?;
    Ok(draft.design)
}

/// Refuses an ensemble of `runs` > 1 runs together with an initial ball offset given by the
/// user (`ball_position_given`): the ensemble sets the offsets itself
/// ([`crate::ensemble::ball_positions`]). The message names both, as `spelling` spells them.
pub fn check_ensemble(runs: usize, ball_position_given: bool, spelling: Spelling) -> Result<(), ThudError> {
    if runs > 1 && ball_position_given {
        return Err(ThudError::invalid(
            spelling.spell("ball-position"),
            format!(
                "cannot be combined with {} {runs}: the ensemble sets the ball's initial offsets, y0 = −d/2 + (k + ½)·d/N",
                spelling.spell("ensemble")
            ),
        ));
    }
    Ok(())
}

/// How to ask for the Newmark solver, as the front end's user types it.
fn solver_hint(spelling: Spelling) -> &'static str {
    match spelling {
        Spelling::Flag => "--solver newmark",
        Spelling::Keyword => "solver=\"newmark\"",
    }
}

/// An observer inside the ball is the ball's fault when the user sized the ball and left the
/// observer alone: name the parameter they typed, not `r`.
fn blame_ball(given: &Given<DesignDraft>, e: ThudError, d: &Design) -> ThudError {
    if given.has("r") || e.param() != "r" {
        return given.respell(e);
    }
    match ["mass", "density", "radius"].into_iter().find(|n| given.has(n)) {
        Some(name) => ThudError::invalid(
            given.spell(name),
            format!(
                "the ball's radius {} m reaches the observer at r {} m; make the ball smaller or move the observer with {}",
                short(d.ball_radius_m()),
                short(d.observer.r_m),
                given.spell("r")
            ),
        ),
        None => given.respell(e),
    }
}
