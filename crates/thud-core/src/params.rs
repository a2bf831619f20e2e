//! Parameters by name: the one mapping from named inputs — the command line's long flags
//! (`--main-mass 0.5`) and Python's keywords (`main_mass=0.5`) — to a checked design
//! ([`ValidDesign`]) or a single impact ([`PulseInput`]). Every number is checked against its range in
//! [`crate::limits`] (the one range table), so every front end accepts and refuses the same
//! values with the same one-line message.
//!
//! A front end hands in `(name, Input)` pairs, names as [`Spelling::key`] spells them: the long
//! flags without dashes (`main-mass`) from the command line, keywords (`main_mass`) from Python. The tables [`DESIGN`] and [`PULSE`] list the known names; values are parsed
//! and applied in table order (not the order given), so every front end reports the same first
//! problem. Messages name the parameter the way the front end's user typed it ([`Spelling`]):
//! `invalid --main-mass: …` on the command line, `invalid main_mass: …` in Python.
//!
//! Adding a parameter to a design is one line in [`DESIGN`]: its name, what it accepts
//! (a quantity of a [`Kind`] inside a [`Range`], a choice of names, a name or a switch) and
//! where it goes. The command line's flags (its help, completions and man page), Python's
//! keywords and the explorer's fields are then built from the row; so are `thud pulse`'s from
//! the rows of [`PULSE`].

use crate::acoustics::{Air, Field, Observer, PulseShape, QuadSigns, Radiation, Source};
use crate::contact::{self, Contact, Impact, Target};
use crate::damper::Solver;
use crate::design::{BallSize, Design, Materials, Model, ValidDesign};
use crate::error::ThudError;
use crate::limits::{self, short, Range};
use crate::units::{self, Kind};

/// A value as a front end received it.
#[derive(Debug, Clone, PartialEq)]
pub enum Input {
    /// A number in the plain unit of the parameter's range (SI; degrees, dB, cm/s where the
    /// range says so).
    Num(f64),
    /// Text as typed: a number with or without a unit (`40.5g`), or a name (`dipole`).
    Text(String),
    /// A switch turned on or off (`no-tension`).
    Switch(bool),
    /// A value of a type the front end has no engine value for, described for the message
    /// (`a list`).
    Other(String),
}

impl Input {
    /// The value as typed, for a message: `'5Hz'` for text, the number otherwise.
    fn shown(&self) -> String {
        match self {
            Input::Num(v) => short(*v),
            other => other.describe(),
        }
    }

    /// What the value is, for a message about a value of the wrong type.
    fn describe(&self) -> String {
        match self {
            Input::Num(_) => "a number".to_string(),
            Input::Text(t) => format!("'{t}'"),
            Input::Switch(_) => "a switch (True or False)".to_string(),
            Input::Other(what) => what.clone(),
        }
    }
}

/// How a front end spells a parameter's name in messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spelling {
    /// The command line's long flag: `--main-mass`.
    Flag,
    /// A Python keyword: `main_mass`.
    Keyword,
}

impl Spelling {
    /// How a front end hands in the name `name` of the tables: the command line as in the
    /// tables (`main-mass`), Python as its keyword (`main_mass`).
    pub fn key(self, name: &str) -> String {
        match self {
            Spelling::Flag => name.to_string(),
            Spelling::Keyword => self.spell(name),
        }
    }

    /// `name` (as in the tables, `main-mass`) as the user typed it.
    pub fn spell(self, name: &str) -> String {
        match self {
            Spelling::Flag => format!("--{name}"),
            Spelling::Keyword => name.replace('-', "_"),
        }
    }
}

/// What one parameter accepts, and where its value goes in the draft `T`.
pub enum Accepts<T: 'static> {
    /// A quantity of `kind` inside `range` (a plain number is in the range's unit).
    Quantity { kind: Kind, range: &'static Range, set: fn(&mut T, f64) },
    /// One of `names` (each with a line of help in `helps`, or none); `set` gets the index of
    /// the name. `type_name` is the type of the choice in Python's stubs (`Solver`).
    Choice {
        names: &'static [&'static str],
        helps: &'static [&'static str],
        type_name: &'static str,
        set: fn(&mut T, usize),
    },
    /// A name the engine checks itself (a material).
    Name { set: fn(&mut T, &str) },
    /// On or off.
    Switch { set: fn(&mut T, bool) },
    /// A whole number inside `range` (a number, or text such as `1e4`; see [`Range::parse_count`]).
    Count { range: &'static Range, set: fn(&mut T, usize) },
}

/// What part of a study a parameter belongs to: the explorer groups its fields by it, and the
/// documentation lists them so.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Group {
    /// The damper and its structure: masses, gap, springs, contact, materials, the ball.
    Design,
    /// The harmonic force on the main mass and the ball's start.
    Forcing,
    /// Where the sound is heard and how it is radiated.
    Listener,
    /// How the run is computed: solver, time step, simulated time, windows.
    Solver,
    /// How a result is judged: the zone thresholds.
    Study,
}

impl Group {
    /// Every group, in the order the explorer lists them.
    pub const ALL: [Group; 5] = [Group::Design, Group::Forcing, Group::Listener, Group::Solver, Group::Study];

    /// The group's heading.
    pub fn title(self) -> &'static str {
        match self {
            Group::Design => "design",
            Group::Forcing => "forcing",
            Group::Listener => "listener",
            Group::Solver => "solver",
            Group::Study => "study",
        }
    }
}

/// Two parameters that cannot be given together, declared on one row (where the command line
/// declares it too, e.g. in its completions).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Conflict {
    /// The other parameters (each refused with this row, in this order).
    pub with: &'static [&'static str],
    /// Why, for the message ("K_HZ follows from the materials").
    pub why: &'static str,
    /// Whether the message names the other parameter (the one whose value would be ignored)
    /// rather than this row.
    pub names_other: bool,
}

/// One named parameter: one row of a table, from which every front end takes its flag, keyword,
/// field, help, range and check.
pub struct Param<T: 'static> {
    /// The long flag without dashes (`main-mass`).
    pub name: &'static str,
    /// Another name a front end may hand the parameter in under (`force-amplitude` for `force`,
    /// on commands whose `--force` means "replace the file"); messages then name it as given.
    pub alias: Option<&'static str>,
    pub accepts: Accepts<T>,
    /// One line for people: the command line's help, Python's stub comment, the explorer's hint.
    pub help: &'static str,
    /// The value's placeholder in usage lines (`M` in `--mass <M>`; empty: the name in capitals).
    pub value_name: &'static str,
    /// A label of at most 10 characters for a panel row (`ball w0`); the name if it is short.
    pub label: &'static str,
    pub group: Group,
    /// Another parameter this one cannot be given with ([`Conflict`]).
    pub conflicts: Option<Conflict>,
    /// Another parameter this one needs (`plate` needs `sphere`).
    pub requires: Option<&'static str>,
    /// The value in a design (internal units), for numeric rows of [`DESIGN`]: what a front end
    /// shows as the current or default value.
    pub get: Option<fn(&Design) -> f64>,
    /// Whether a design holds the row's value (None: every design does): K_HZ is not a design's
    /// own when its materials set it, nor a frequency without a force. [`check_design`] checks
    /// the value against the row's range wherever the row applies.
    pub applies: Option<fn(&Design) -> bool>,
}

impl<T> Param<T> {
    /// Shorthand: a row of `group` with no placeholder, relation or accessor yet.
    const fn new(name: &'static str, group: Group, accepts: Accepts<T>, help: &'static str) -> Self {
        Param {
            name,
            alias: None,
            accepts,
            help,
            value_name: "",
            label: name,
            group,
            conflicts: None,
            requires: None,
            get: None,
            applies: None,
        }
    }

    /// The row with the placeholder `value_name`.
    const fn value(mut self, value_name: &'static str) -> Self {
        self.value_name = value_name;
        self
    }

    /// The row with the panel label `label`.
    const fn label(mut self, label: &'static str) -> Self {
        self.label = label;
        self
    }

    /// The row with the accessor `get`.
    const fn get(mut self, get: fn(&Design) -> f64) -> Self {
        self.get = Some(get);
        self
    }

    /// The row applying only to the designs for which `applies` holds.
    const fn applies(mut self, applies: fn(&Design) -> bool) -> Self {
        self.applies = Some(applies);
        self
    }

    /// The row's range, for quantity and count rows.
    pub fn range(&self) -> Option<&'static Range> {
        match self.accepts {
            Accepts::Quantity { range, .. } | Accepts::Count { range, .. } => Some(range),
            _ => None,
        }
    }

    /// One line documenting the row, generated (no hand-written copy anywhere): its help (or,
    /// without one, what its range is, or the help of the [`DESIGN`] row of its name), its
    /// range, and its alias as `spelling` spells it — `Impact mass m (kg, or e.g. 40.5g);
    /// 0.0001 to 100 kg`. Python's stub comments and docstrings are these lines.
    pub fn doc_line(&self, spelling: Spelling) -> String {
        let help = match (self.help, self.range()) {
            ("", Some(r)) => {
                let mut what = r.what.chars();
                what.next().map_or(String::new(), |c| c.to_uppercase().chain(what).collect())
            }
            ("", None) => design_param(self.name).map_or("", |p| p.help).to_string(),
            (help, _) => help.to_string(),
        };
        let range = self.range().map_or(String::new(), |r| format!("; {}", r.describe()));
        let alias = self.alias.map_or(String::new(), |a| format!(" (alias {})", spelling.spell(a)));
        format!("{help}{range}{alias}")
    }

    /// The unit of a plain number (empty for counts, names, choices and switches).
    pub fn unit(&self) -> &'static str {
        match self.accepts {
            Accepts::Quantity { kind, .. } => kind.plain_unit(),
            _ => "",
        }
    }
}

/// The names of the solvers, as on the command line.
pub const SOLVERS: [&str; 2] = ["event", "newmark"];
/// What each solver is ([`SOLVERS`] order).
const SOLVER_HELPS: [&str; 2] = [
    "Exact flight between impacts, adaptive integration inside each contact (fast)",
    "Uniform Newmark-β (β 1/4, γ 1/2) at --dt: the paper's method, the reference",
];
/// The names of the source types, in [`Source::ALL`] order.
pub const SOURCES: [&str; 3] = ["single", "dipole", "quadrupole"];
/// The names of the quadrupole wall-image signs.
pub const QUAD_SIGNS: [&str; 2] = ["paper", "rigid"];
/// The names of the acceleration pulse shapes.
pub const PULSES: [&str; 2] = ["half-sine", "hertz"];
/// What each pulse shape is ([`PULSES`] order).
const PULSE_HELPS: [&str; 2] = ["The paper's half-sine, Eq 7", "The exact Hertz pulse"];

/// The names of the models, in [`Model::ALL`] order.
pub const MODELS: [&str; 2] = ["paper", "physical"];
/// What each model is ([`MODELS`] order).
const MODEL_HELPS: [&str; 2] = [
    "The paper's: rms level over τ, half-sine pulse, its air and K_HZ (reproduces the paper)",
    "The measured world: peak level, exact Hertz pulse, air from temperature and pressure, K_HZ and mass from the materials",
];

/// The help of the air-temperature rows ([`DESIGN`] and [`PULSE`] alike).
const AIR_TEMPERATURE_HELP: &str = "Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]";
/// The help of the air-pressure rows ([`DESIGN`] and [`PULSE`] alike).
const AIR_PRESSURE_HELP: &str =
    "Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325]";

fn model(i: usize) -> Model {
    Model::ALL[i.min(1)]
}

fn source(i: usize) -> Source {
    Source::ALL[i.min(2)]
}

fn quad_signs(i: usize) -> QuadSigns {
    if i == 0 {
        QuadSigns::Paper
    } else {
        QuadSigns::Rigid
    }
}

fn pulse_shape(i: usize) -> PulseShape {
    if i == 0 {
        PulseShape::HalfSine
    } else {
        PulseShape::Hertz
    }
}

/// A design being built from a base design and named parameters.
#[derive(Debug, Clone)]
pub struct DesignDraft {
    pub design: Design,
    /// `solver`, as an index into [`SOLVERS`].
    solver: Option<usize>,
    dt_s: Option<f64>,
    sphere: Option<String>,
    plate: Option<String>,
    /// The ball's Poisson ratio ν, for the materials `sphere` names.
    sphere_nu: Option<f64>,
    /// The ball's radius (m) and density (kg/m³) as given, for [`resolve_ball`].
    radius_m: Option<f64>,
    density_kg_m3: Option<f64>,
}

impl DesignDraft {
    /// A draft of `design` with nothing given yet.
    fn of(design: Design) -> Self {
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

/// The parameters of a design (`simulate`, `sweep`, `export`, `response`; Python's `simulate`,
/// `sweep`, `response`; the explorer's fields), in the order they are checked and listed.
/// Each row is the one definition of its parameter: the command line's flag (and its help,
/// completion and man page), Python's keyword (and its stub), the explorer's field, its range
/// ([`crate::limits`]) and where its value goes.
#[rustfmt::skip]
pub const DESIGN: &[Param<DesignDraft>] = &[
    q("mass", Kind::Mass, &limits::MASS, Group::Design, "M", "Impact mass m (kg, or e.g. 40.5g)",
        |d| d.damper.impact_mass_kg, |d, v| d.design.damper.impact_mass_kg = v),
    q("gap", Kind::Length, &limits::GAP, Group::Design, "D", "Total clearance d (m, or e.g. 4cm)",
        |d| d.damper.gap_m, |d, v| d.design.damper.gap_m = v),
    q("v0", Kind::Speed, &limits::V0, Group::Forcing, "V", "Initial velocity of the main mass (m/s)",
        |d| d.damper.v0_m_s, |d, v| d.design.damper.v0_m_s = v),
    q("main-mass", Kind::Mass, &limits::MAIN_MASS, Group::Design, "MM", "Main mass M (kg)",
        |d| d.damper.main_mass_kg, |d, v| d.design.damper.main_mass_kg = v),
    q("k", Kind::Stiffness, &limits::STIFFNESS, Group::Design, "K", "Spring stiffness K (N/m)",
        |d| d.damper.stiffness_n_m, |d, v| d.design.damper.stiffness_n_m = v),
    q("c", Kind::Damping, &limits::DAMPING, Group::Design, "C", "Viscous damping C (N·s/m)",
        |d| d.damper.damping_n_s_m, |d, v| d.design.damper.damping_n_s_m = v),
    q("c1", Kind::Damping, &limits::C1, Group::Design, "C1", "Contact damping c1 (N·s/m)",
        |d| d.damper.c1_n_s_m, |d, v| d.design.damper.c1_n_s_m = v),
    Param {
        conflicts: Some(Conflict { with: &["sphere"], why: "K_HZ follows from the materials", names_other: false }),
        ..q("k-hz", Kind::HertzStiffness, &limits::K_HZ, Group::Design, "KH", "Hertz stiffness K_HZ (N/m^1.5)",
            |d| d.damper.k_hz, |d, v| d.design.damper.k_hz = v).applies(|d| d.materials_used().is_none())
    },
    Param::new("sphere", Group::Design, Accepts::Name { set: |d: &mut DesignDraft, s| d.sphere = Some(s.to_string()) },
        "Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2)").value("MATERIAL"),
    Param {
        requires: Some("sphere"),
        ..Param::new("plate", Group::Design, Accepts::Name { set: |d: &mut DesignDraft, s| d.plate = Some(s.to_string()) },
            "Enclosure material (with --sphere) [default: steel]").value("MATERIAL")
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
        .applies(|d| matches!(d.ball, BallSize::Density(_))),
    q("radius", Kind::Length, &limits::RADIUS, Group::Design, "A",
        "Ball radius (m): with --mass as given, else the mass follows from the density",
        Design::ball_radius_m, |d, v| { d.design.ball = BallSize::Radius(v); d.radius_m = Some(v); }).label("ball a")
        .applies(|d| matches!(d.ball, BallSize::Radius(_))),
    q("r", Kind::Length, &limits::R, Group::Listener, "R", "Observer distance (m)",
        |d| d.observer.r_m, |d, v| d.design.observer.r_m = v),
    q("theta", Kind::Angle, &limits::THETA, Group::Listener, "DEG", "Observer angle (degrees)",
        |d| d.observer.theta_rad.to_degrees(), |d, v| d.design.observer.theta_rad = v.to_radians()),
    ch("source", Group::Listener, &SOURCES, &[], "Source", "Reflecting surfaces around the impact",
        |d, i| d.design.radiation.source = source(i)),
    ch("quad-signs", Group::Listener, &QUAD_SIGNS, &[], "QuadSigns", "Quadrupole wall-image signs",
        |d, i| d.design.radiation.quad_signs = quad_signs(i)),
    ch("pulse", Group::Listener, &PULSES, &PULSE_HELPS, "PulseShape",
        "Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse",
        |d, i| d.design.radiation.pulse = pulse_shape(i)),
    Param {
        get: Some(|d| if d.model == Model::Physical { 1.0 } else { 0.0 }),
        ..ch("model", Group::Listener, &MODELS, &MODEL_HELPS, "Model",
            "The model of the world [default: paper]: physical is the level a microphone reads (peak, real air, materials)",
            |d, i| d.design.model = model(i))
    },
    q("air-temperature", Kind::Temperature, &limits::AIR_TEMPERATURE, Group::Listener, "T", AIR_TEMPERATURE_HELP,
        |d| d.atmosphere.temperature_c, |d, v| d.design.atmosphere.temperature_c = v).label("air T"),
    q("air-pressure", Kind::Pressure, &limits::AIR_PRESSURE, Group::Listener, "P", AIR_PRESSURE_HELP,
        |d| d.atmosphere.pressure_pa, |d, v| d.design.atmosphere.pressure_pa = v).label("air p"),
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
    // The air is no row of the table (a single impact's parameters, [`PULSE`]).
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
    let mut out = String::new();
    for p in DESIGN.iter().filter(|p| !skip.contains(&p.name)) {
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
        // Only a choice that sets the design alone reads its index back (`get`): the model.
        Accepts::Choice { set, names, .. } if p.get.is_some() => {
            if value.is_finite() && value >= 0.0 && value < names.len() as f64 {
                set(&mut draft, value as usize);
            }
        }
        Accepts::Choice { .. } | Accepts::Name { .. } => {}
    }
    draft.design
}

/// The named parameters a front end received, checked against a table: no unknown name, no
/// name twice.
struct Given<'a, T: 'static> {
    table: &'static [Param<T>],
    /// Each parameter given, its value, and the name it was given under (its name or alias).
    values: Vec<(&'static Param<T>, &'a Input, &'static str)>,
    spelling: Spelling,
}

impl<'a, T> Given<'a, T> {
    fn new(table: &'static [Param<T>], pairs: &'a [(String, Input)], spelling: Spelling) -> Result<Self, ThudError> {
        let mut values: Vec<(&'static Param<T>, &'a Input, &'static str)> = Vec::with_capacity(pairs.len());
        for (name, value) in pairs {
            let found = table.iter().find_map(|p| {
                std::iter::once(p.name).chain(p.alias).find(|n| spelling.key(n) == *name).map(|n| (p, n))
            });
            let Some((p, as_named)) = found else {
                return Err(unknown(table, name, spelling));
            };
            if values.iter().any(|(q, _, _)| q.name == p.name) {
                return Err(ThudError::invalid(spelling.spell(as_named), "is given twice"));
            }
            values.push((p, value, as_named));
        }
        // Table order, whatever the order given.
        values.sort_by_key(|(p, _, _)| table.iter().position(|q| q.name == p.name));
        Ok(Given { table, values, spelling })
    }

    fn has(&self, name: &str) -> bool {
        self.values.iter().any(|(p, _, _)| p.name == name)
    }

    /// The parameter `name` (of the table) as the user typed it: under the alias they used,
    /// if they did.
    fn spell(&self, name: &str) -> String {
        let typed = self.values.iter().find(|(p, _, _)| p.name == name).map_or(name, |(_, _, n)| n);
        self.spelling.spell(typed)
    }

    /// Parses every value and applies it to `draft`, in table order.
    fn apply(&self, draft: &mut T) -> Result<(), ThudError> {
        for (p, value, _) in &self.values {
            let flag = self.spell(p.name);
            match (&p.accepts, value) {
                (Accepts::Quantity { range, set, .. }, Input::Num(v)) => set(draft, range.check_as(&flag, *v)?),
                (Accepts::Quantity { kind, range, set }, Input::Text(t)) => {
                    set(draft, range.check_as(&flag, units::parse(&flag, t, *kind)?)?);
                }
                (Accepts::Choice { names, set, .. }, Input::Text(t)) => match names.iter().position(|n| n == t) {
                    Some(i) => set(draft, i),
                    None => {
                        return Err(ThudError::invalid(
                            flag,
                            format!("unknown value '{t}'; one of: {}", names.join(", ")),
                        ))
                    }
                },
                (Accepts::Name { set }, Input::Text(t)) => set(draft, t),
                (Accepts::Switch { set }, Input::Switch(on)) => set(draft, *on),
                (Accepts::Count { range, set }, Input::Text(t)) => set(draft, range.parse_count(&flag, t)?),
                (Accepts::Count { range, set }, Input::Num(v)) => {
                    set(draft, range.parse_count(&flag, &format!("{v}"))?);
                }
                (accepts, v) => {
                    return Err(ThudError::invalid(
                        flag,
                        format!("expected {}, not {}", expected(accepts), v.describe()),
                    ))
                }
            }
        }
        Ok(())
    }

    /// An engine error that names a parameter of the table bare (`mass`) named as typed.
    fn respell(&self, mut e: ThudError) -> ThudError {
        if self.table.iter().any(|p| p.name == e.param()) {
            let spelled = self.spell(e.param());
            e = e.renamed(spelled);
        }
        e
    }

    /// Refuses what the table's rows say cannot go together: a row given with the one it
    /// conflicts with, or without the one it needs (table order).
    fn relations(&self) -> Result<(), ThudError> {
        for p in self.table {
            let Some(c) = p.conflicts else { continue };
            for with in c.with {
                if c.names_other {
                    self.conflict(p.name, with, c.why)?;
                } else {
                    self.conflict(with, p.name, c.why)?;
                }
            }
        }
        for p in self.table {
            if let Some(needed) = p.requires.filter(|n| self.has(p.name) && !self.has(n)) {
                return Err(ThudError::Requires { param: self.spell(p.name), needs: self.spell(needed) });
            }
        }
        Ok(())
    }

    /// Refuses two parameters given together that contradict each other.
    fn conflict(&self, a: &str, b: &str, why: &'static str) -> Result<(), ThudError> {
        if self.has(a) && self.has(b) {
            return Err(ThudError::Conflict { param: self.spell(b), with: self.spell(a), why });
        }
        Ok(())
    }
}

/// What a parameter accepts, for a message about a value of the wrong type.
fn expected<T>(accepts: &Accepts<T>) -> String {
    match accepts {
        Accepts::Quantity { kind, .. } => match kind.plain_unit() {
            "" => "a number".to_string(),
            unit => format!("a number in {unit} or a text with a unit"),
        },
        Accepts::Choice { names, .. } => format!("one of: {}", names.join(", ")),
        Accepts::Name { .. } => "a name".to_string(),
        Accepts::Switch { .. } => "on or off (a switch)".to_string(),
        Accepts::Count { .. } => "a whole number".to_string(),
    }
}

/// "unknown parameter; did you mean …? (one of: …)".
fn unknown<T>(table: &[Param<T>], name: &str, spelling: Spelling) -> ThudError {
    let canonical = name.replace('_', "-");
    let near = table.iter().map(|p| (edit_distance(&canonical, p.name), p.name)).min_by_key(|&(d, _)| d);
    let all: Vec<String> = table.iter().map(|p| spelling.spell(p.name)).collect();
    let hint = match near {
        Some((d, n)) if d <= 2 => format!("did you mean {}? ", spelling.spell(n)),
        _ => String::new(),
    };
    let shown = match spelling {
        Spelling::Flag => spelling.spell(name),
        Spelling::Keyword => name.to_string(),
    };
    ThudError::invalid(shown, format!("unknown parameter; {hint}(one of: {})", all.join(", ")))
}

/// Levenshtein distance between two short names (for "did you mean").
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
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

/// The ball's size as a front end gave it: each of its three numbers, if given, and its
/// material's name and density (kg/m³), if the ball has a material.
#[derive(Debug, Clone, Copy, Default)]
struct BallGiven {
    mass_kg: Option<f64>,
    radius_m: Option<f64>,
    density_kg_m3: Option<f64>,
    material: Option<(&'static str, f64)>,
}

/// A base's ball as its mass (kg) and how its size follows.
#[derive(Debug, Clone, Copy)]
struct BaseBall {
    mass_kg: f64,
    size: BallSize,
}

fn base_ball_of(size: &BallSize, mass_kg: f64) -> BaseBall {
    BaseBall { mass_kg, size: *size }
}

/// Relative disagreement (of the mass) tolerated between a mass, a radius and a density all
/// given: 0.1 %, what typing four significant digits of each allows.
const BALL_TOLERANCE: f64 = 1e-3;

/// THE resolution of one ball, the same for every command, Python and the explorer: its mass
/// (kg) and how its radius follows ([`BallSize`]), from the `base` ball and what was `given`.
/// A ball is fixed by two of mass, radius and density; a material names a density.
///
/// * mass, radius and density: all three must agree (to [`BALL_TOLERANCE`]), else refused in
///   one line naming the three (`spell` spells a row's name as the user typed it);
/// * two of them: the third follows (mass and radius given keep both, the material's density
///   aside: the ball is then not solid material);
/// * one, or none: the material's density (if it has one), else the base's, fills in; with a
///   material and only a radius (given, or the base's fixed radius) the mass follows.
fn resolve_ball(base: BaseBall, g: &BallGiven, spell: impl Fn(&str) -> String) -> Result<(f64, BallSize), ThudError> {
    use contact::sphere_mass;
    let material = g.material.map(|(_, rho)| rho);
    let (mass, size, from) = match (g.mass_kg, g.radius_m, g.density_kg_m3) {
        (Some(m), Some(r), Some(rho)) => {
            let implied = sphere_mass(r, rho);
            if (implied - m).abs() > BALL_TOLERANCE * m {
                return Err(ThudError::invalid(
                    spell("density"),
                    format!(
                        "{} {} kg, {} {} m and {} {} kg/m^3 disagree: that radius and density make {} kg; give two of the three",
                        spell("mass"),
                        short(m),
                        spell("radius"),
                        short(r),
                        spell("density"),
                        short(rho),
                        short(implied)
                    ),
                ));
            }
            (m, BallSize::Density(rho), None)
        }
        (Some(m), Some(r), None) => (m, BallSize::Radius(r), None),
        (None, Some(r), Some(rho)) => (sphere_mass(r, rho), BallSize::Density(rho), Some(("radius", r, rho))),
        (None, Some(r), None) => match material {
            Some(rho) => (sphere_mass(r, rho), BallSize::Density(rho), Some(("radius", r, rho))),
            None => (base.mass_kg, BallSize::Radius(r), None),
        },
        (m, None, Some(rho)) => (m.unwrap_or(base.mass_kg), BallSize::Density(rho), None),
        (m, None, None) => match (material, base.size, m) {
            (Some(rho), BallSize::Radius(r), None) => {
                (sphere_mass(r, rho), BallSize::Density(rho), Some(("radius", r, rho)))
            }
            (Some(rho), _, m) => (m.unwrap_or(base.mass_kg), BallSize::Density(rho), None),
            (None, size, m) => (m.unwrap_or(base.mass_kg), size, None),
        },
    };
    // A mass that follows from a radius must be inside the mass range: named by the radius
    // when it was typed (else the material made it).
    if let Some((_, r, rho)) = from.filter(|_| !limits::MASS.contains(mass)) {
        let by = if g.radius_m.is_some() { "radius" } else { "sphere" };
        return Err(ThudError::invalid(
            spell(by),
            format!(
                "a ball of radius {} m at {} kg/m^3 weighs {} kg; the {} must be {}",
                short(r),
                short(rho),
                short(mass),
                limits::MASS.what,
                limits::MASS.describe()
            ),
        ));
    }
    Ok((mass, size))
}

/// `design` with its ball resolved for its material (`resolve_ball`, the rule every front end
/// uses): a design whose materials (or physical model) name a ball material takes that
/// material's density, its mass kept (or, for a ball of fixed radius, its radius kept and its
/// mass following). The explorer calls this when its materials field changes. A design
/// without a ball material is returned as it is; a mass outside its range is an error.
pub fn follow_material(mut design: Design) -> Result<Design, ThudError> {
    let Some(m) = design.materials_used() else { return Ok(design) };
    let s = m.sphere_material()?;
    let ball = BallGiven { material: Some((s.name, s.density_kg_m3)), ..BallGiven::default() };
    let (mass, size) =
        resolve_ball(base_ball_of(&design.ball, design.damper.impact_mass_kg), &ball, ToString::to_string)?;
    design.damper.impact_mass_kg = mass;
    design.ball = size;
    Ok(design)
}

/// Refuses what the physical model derives itself, given together with it: K_HZ (Eq 2 from the
/// materials) and the pulse shape (the exact Hertz pulse).
fn physical_conflicts<T>(given: &Given<T>, model: Model) -> Result<(), ThudError> {
    if model != Model::Physical {
        return Ok(());
    }
    for (name, why) in [
        ("k-hz", "the physical model takes K_HZ from the materials (Eq 2)"),
        ("pulse", "the physical model uses the exact Hertz pulse"),
        ("rho-c", "the physical model takes the air from its temperature and pressure"),
        ("sound-speed", "the physical model takes the air from its temperature and pressure"),
    ] {
        if given.has(name) {
            let with = if given.has("model") {
                format!("{} physical", given.spell("model"))
            } else {
                "a physical-model design".to_string()
            };
            return Err(ThudError::Conflict { param: given.spell(name), with, why });
        }
    }
    Ok(())
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

/// "FROM:TO:N" (e.g. `30g:100g:20`) as N evenly spaced quantities of `kind` ([`crate::design::linspace`]);
/// both ends are checked against `range`, N against [`limits::GRID_N`]. `param` names the
/// parameter in errors, as typed (`--masses`).
pub fn parse_range(param: &str, text: &str, kind: Kind, range: &Range) -> Result<Vec<f64>, ThudError> {
    let parts: Vec<&str> = text.split(':').collect();
    let [from, to, n] = parts[..] else {
        let example = match kind {
            Kind::Mass => "30g:100g:20",
            Kind::Length => "2cm:5cm:20",
            Kind::Frequency => "3Hz:8Hz:101",
            _ => "1:10:10",
        };
        return Err(ThudError::invalid(param, format!("'{text}'; expected FROM:TO:N, e.g. {example}")));
    };
    let from = range.check_as(param, units::parse(param, from, kind)?)?;
    let to = range.check_as(param, units::parse(param, to, kind)?)?;
    let n = limits::GRID_N.parse_count(param, n)?;
    Ok(crate::design::linspace(from, to, n))
}

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
        ..pq("k-hz", Kind::HertzStiffness, design_range("k-hz"), "K",
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
    Ok(PulseInput {
        radius_m,
        impact,
        observer,
        radiation: Radiation { source, quad_signs, air, pulse },
        model,
        typed: (given.has("radius"), given.has("mass"), given.has("r"), spelling),
    })
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

#[cfg(test)]
mod tests {
    use super::*;

    fn text(pairs: &[(&str, &str)]) -> Vec<(String, Input)> {
        pairs.iter().map(|(n, v)| (n.to_string(), Input::Text(v.to_string()))).collect()
    }

    fn err<T: std::fmt::Debug>(r: Result<T, ThudError>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn the_default_design_and_presets_like_it_are_in_range() {
        check_design(&Design::default()).unwrap();
        check_design(&Design::paper_table3()).unwrap();
    }

    #[test]
    fn check_design_refuses_an_out_of_range_field_by_name() {
        let mut d = Design::default();
        d.damper.stiffness_n_m = 1e308;
        assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid k: "));
        let d = Design { ball: BallSize::Density(1e308), ..Design::default() };
        assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid density: "));
        let mut d = Design::default();
        d.thresholds.inclination_cm_s = -5.0;
        assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid e-star: "));
    }

    /// The check is the table's: for every row of [`DESIGN`] with a range, a design with that
    /// one value below its range, above it or NaN (on a design the row applies to) is refused
    /// by [`Design::check`], and [`check_design`] names the row.
    #[test]
    fn a_design_with_any_single_row_out_of_range_is_refused() {
        let materials = Materials { sphere: "steel".into(), plate: "steel".into(), sphere_nu: Some(0.3) };
        // Designs between them every row applies to: the default (a density ball, the event
        // solver, no materials, no force), a ball of a given radius, the Newmark solver, materials.
        let bases = [
            Design::default(),
            Design { ball: BallSize::Radius(0.01), ..Design::default() },
            Design { solver: Solver::Newmark { dt_s: NEWMARK_DT_S }, ..Design::default() },
            Design { materials: Some(materials), ..Design::default() },
        ];
        for p in DESIGN {
            let Some(range) = p.range() else { continue };
            assert_eq!(range.param, p.name, "the range of a row names the row");
            let get = p.get.unwrap_or_else(|| panic!("{}: a row with a range reads its value", p.name));
            let mut refused = 0;
            let wide = |b: f64| b.abs().max(1.0);
            for v in [range.min - wide(range.min), range.max + wide(range.max), f64::NAN] {
                // The row's value set to v: the Newmark step is the solver's, not a design value.
                let with = |base: &Design| match p.name {
                    "dt" => Design { solver: Solver::Newmark { dt_s: v }, ..base.clone() },
                    _ => set_number(base, p, v),
                };
                let Some(d) = bases.iter().map(with).find(|d| p.applies.is_none_or(|applies| applies(d))) else {
                    panic!("{}: no design the row applies to", p.name)
                };
                if range.contains(get(&d)) {
                    continue; // a count cannot hold v (NaN, or below 0)
                }
                assert!(d.clone().check().is_err(), "{} = {v} passed Design::check", p.name);
                let e = check_design(&d).unwrap_err();
                assert_eq!(e.param(), p.name, "{} = {v}: {e}", p.name);
                refused += 1;
            }
            assert!(refused >= 2, "{}: only {refused} of its out-of-range values could be set", p.name);
        }
    }

    /// A row is checked only where it applies: K_HZ that materials set, a frequency without a
    /// force, a Newmark step of the event solver, a density of a ball of given radius.
    #[test]
    fn a_row_that_does_not_apply_is_not_checked() {
        let materials = Materials { sphere: "steel".into(), plate: "steel".into(), sphere_nu: None };
        let mut d = Design { materials: Some(materials), ..Design::default() };
        d.damper.k_hz = 0.0;
        check_design(&d).unwrap();
        let mut d = Design { ball: BallSize::Radius(0.01), ..Design::default() };
        d.damper.freq_hz = 0.0;
        d.damper.force_n = 0.0;
        check_design(&d).unwrap();
        d.damper.force_n = 1.0;
        assert_eq!(check_design(&d).unwrap_err().param(), "freq", "a force needs a frequency");
    }

    #[test]
    fn numbers_and_texts_with_units_give_the_same_design() {
        let a = design(Design::default(), &text(&[("mass", "0.05"), ("gap", "3cm")]), Spelling::Flag).unwrap();
        let b = design(
            Design::default(),
            &[("gap".into(), Input::Num(0.03)), ("mass".into(), Input::Num(0.05))],
            Spelling::Keyword,
        )
        .unwrap();
        assert_eq!(a, b);
        assert_eq!(a.damper.impact_mass_kg, 0.05);
        assert_eq!(a.damper.gap_m, 0.03);
    }

    #[test]
    fn no_parameters_leave_the_base_as_it_is() {
        assert_eq!(design(Design::paper_fig9(), &[], Spelling::Flag).unwrap(), Design::paper_fig9());
    }

    #[test]
    fn errors_name_the_parameter_as_the_front_end_spells_it() {
        let e = err(design(Design::default(), &text(&[("main-mass", "1e308")]), Spelling::Flag));
        assert!(e.starts_with("invalid --main-mass: 1e308 kg is out of range; the main mass M must be"), "{e}");
        let e = err(design(Design::default(), &[("main_mass".into(), Input::Num(1e308))], Spelling::Keyword));
        assert!(e.starts_with("invalid main_mass: 1e308 kg is out of range; the main mass M must be"), "{e}");
        let e = err(design(Design::default(), &[("gap".into(), Input::Num(f64::NAN))], Spelling::Keyword));
        assert!(e.starts_with("invalid gap: NaN is not a finite number"), "{e}");
        let e = err(design(Design::default(), &[("gap".into(), Input::Num(f64::INFINITY))], Spelling::Keyword));
        assert!(e.starts_with("invalid gap: inf is not a finite number"), "{e}");
    }

    #[test]
    fn unknown_names_and_wrong_kinds_are_refused() {
        let e = err(design(Design::default(), &[("mas".into(), Input::Num(1.0))], Spelling::Keyword));
        assert!(e.starts_with("invalid mas: unknown parameter; did you mean mass?"), "{e}");
        assert!(e.contains("main_mass") && e.contains("e_star"), "{e}");
        let e = err(design(Design::default(), &[("mass".into(), Input::Switch(true))], Spelling::Keyword));
        assert_eq!(e, "invalid mass: expected a number in kg or a text with a unit, not a switch (True or False)");
        let e = err(design(Design::default(), &[("mass".into(), Input::Other("a list".into()))], Spelling::Keyword));
        assert_eq!(e, "invalid mass: expected a number in kg or a text with a unit, not a list");
        let e = err(design(Design::default(), &[("main-mass".into(), Input::Num(1.0))], Spelling::Keyword));
        assert!(e.starts_with("invalid main-mass: unknown parameter; did you mean main_mass?"), "{e}");
        let e = err(design(Design::default(), &text(&[("source", "monopole")]), Spelling::Keyword));
        assert_eq!(e, "invalid source: unknown value 'monopole'; one of: single, dipole, quadrupole");
        let e = err(design(Design::default(), &[("no_tension".into(), Input::Num(1.0))], Spelling::Keyword));
        assert!(e.starts_with("invalid no_tension: expected on or off"), "{e}");
    }

    #[test]
    fn the_first_problem_in_table_order_is_reported_whatever_the_order_given() {
        let pairs = text(&[("theta", "1e9"), ("mass", "-1")]);
        assert!(err(design(Design::default(), &pairs, Spelling::Flag)).starts_with("invalid --mass: "));
    }

    #[test]
    fn combinations_the_command_line_refuses_in_clap_are_refused_here() {
        // A radius and a density fix the ball's mass (no longer a conflict: issue 23); a mass as
        // well over-determines it, refused when the three disagree.
        let d = design(Design::default(), &text(&[("density", "1000"), ("radius", "1cm")]), Spelling::Keyword).unwrap();
        assert!((d.damper.impact_mass_kg - contact::sphere_mass(0.01, 1000.0)).abs() < 1e-15);
        let e = err(design(
            Design::default(),
            &text(&[("density", "1000"), ("radius", "1cm"), ("mass", "40.5g")]),
            Spelling::Flag,
        ));
        assert!(
            e.starts_with("invalid --density: --mass 0.0405 kg, --radius 0.01 m and --density 1000 kg/m^3 disagree"),
            "{e}"
        );
        let e = err(design(Design::default(), &text(&[("plate", "steel")]), Spelling::Keyword));
        assert_eq!(e, "invalid plate: needs sphere as well");
        let e = err(design(Design::default(), &text(&[("dt", "1e-7")]), Spelling::Keyword));
        assert!(e.contains("add solver=\"newmark\""), "{e}");
    }

    #[test]
    fn solver_materials_and_choices_apply() {
        let d = design(
            Design::default(),
            &text(&[("solver", "newmark"), ("dt", "1e-6"), ("sphere", "steel"), ("source", "dipole")]),
            Spelling::Flag,
        )
        .unwrap();
        assert_eq!(d.solver, Solver::Newmark { dt_s: 1e-6 });
        assert_eq!(d.materials.as_ref().map(|m| m.plate.as_str()), Some("steel"));
        assert_eq!(d.radiation.source, Source::Dipole);
        let steel = contact::material("steel").unwrap();
        assert_eq!(d.damper.k_hz, contact::hertz_stiffness(d.ball_radius_m(), &steel, &steel));
    }

    #[test]
    fn one_ball_whatever_the_command() {
        // A steel ball of 40.5 g: a = (3m/4πρ)^(1/3) = 10.7 mm, for a design and an impact alike.
        let steel = contact::material("steel").unwrap();
        let a = contact::sphere_radius(0.0405, steel.density_kg_m3);
        assert!((a - 0.010_7).abs() < 1e-4, "{a}");
        let given = text(&[("sphere", "steel"), ("mass", "40.5g")]);
        let d = design(Design::default(), &given, Spelling::Flag).unwrap();
        let p = pulse(None, &given, Spelling::Flag).unwrap();
        assert!(
            (d.ball_radius_m() - a).abs() < 1e-15 && (p.radius_m - a).abs() < 1e-15,
            "{} {}",
            d.ball_radius_m(),
            p.radius_m
        );
        assert_eq!((d.damper.impact_mass_kg, p.impact.mass_kg), (0.0405, 0.0405));
        assert_eq!(d.damper.k_hz, p.impact.k_hz, "one ball, one K_HZ");
        // Only a material: the design keeps its mass, the density follows the material.
        let d = design(Design::default(), &text(&[("sphere", "steel")]), Spelling::Flag).unwrap();
        assert!((d.ball_radius_m() - a).abs() < 1e-15);
        // Mass, radius and density that agree are taken.
        let r = format!("{}m", contact::sphere_radius(0.0405, 2000.0));
        let given = text(&[("mass", "40.5g"), ("radius", &r), ("density", "2000")]);
        assert!(design(Design::default(), &given, Spelling::Flag).is_ok());
        let e =
            err(pulse(None, &text(&[("mass", "40.5g"), ("radius", "1cm"), ("density", "2000")]), Spelling::Keyword));
        assert!(
            e.starts_with("invalid density: mass 0.0405 kg, radius 0.01 m and density 2000 kg/m^3 disagree"),
            "{e}"
        );
    }

    #[test]
    fn the_physical_model_derives_air_pulse_and_stiffness_and_refuses_them_given() {
        let d = design(Design::default(), &text(&[("model", "physical")]), Spelling::Flag).unwrap();
        let sound = d.sound();
        assert_eq!(sound.pulse, PulseShape::Hertz);
        assert!((sound.air.rho_c_pa_s_m - 413.29).abs() < 0.01, "{sound:?}");
        let acrylic_on_steel = Materials::new("acrylic", "steel").hertz_stiffness(d.ball_radius_m()).unwrap();
        assert_eq!(d.damper.k_hz, acrylic_on_steel);
        let paper = design(Design::default(), &[], Spelling::Flag).unwrap();
        assert_eq!(paper.sound(), paper.radiation, "the paper's model takes the radiation as given");
        let hot = design(Design::default(), &text(&[("model", "physical"), ("air-temperature", "40")]), Spelling::Flag);
        assert!(hot.unwrap().sound().air.c_m_s > sound.air.c_m_s);
        let e = err(design(Design::default(), &text(&[("model", "physical"), ("k-hz", "5e8")]), Spelling::Flag));
        assert!(e.starts_with("invalid --k-hz: cannot be combined with --model physical"), "{e}");
        let e = err(design(Design::default(), &text(&[("air-temperature", "100")]), Spelling::Flag));
        assert!(e.starts_with("invalid --air-temperature: 100 degC is out of range"), "{e}");
        // A pulse of the physical model: its ball's mass from acrylic's density at Fig 2's radius.
        let p = pulse(None, &text(&[("model", "physical")]), Spelling::Flag).unwrap();
        assert!((p.impact.mass_kg - contact::sphere_mass(0.01905, 1190.0)).abs() < 1e-15);
        assert_eq!(p.radiation.pulse, PulseShape::Hertz);
    }

    #[test]
    fn a_ball_that_reaches_the_observer_blames_what_was_typed() {
        let e = err(design(Design::default(), &text(&[("mass", "100"), ("density", "10")]), Spelling::Keyword));
        assert!(e.starts_with("invalid mass: the ball's radius"), "{e}");
        assert!(e.ends_with("move the observer with r"), "{e}");
    }

    #[test]
    fn ranges_parse_like_the_command_line() {
        let m = parse_range("--masses", "30g:100g:3", Kind::Mass, &limits::MASS).unwrap();
        assert_eq!(m, crate::design::linspace(0.03, 0.1, 3));
        let e = parse_range("masses", "30g:100g", Kind::Mass, &limits::MASS).unwrap_err().to_string();
        assert!(e.starts_with("invalid masses: '30g:100g'; expected FROM:TO:N"), "{e}");
    }

    #[test]
    fn a_pulse_defaults_to_the_paper_s_fig2_impact() {
        let p = pulse(None, &[], Spelling::Flag).unwrap();
        assert_eq!((p.radius_m, p.impact.mass_kg, p.impact.u0_m_s, p.impact.k_hz), (0.01905, 0.0405, 1.4, 5.6e8));
        assert_eq!(p.radiation.source, Source::Dipole);
        let e = pulse(None, &[("u0".into(), Input::Num(-1.0))], Spelling::Keyword).unwrap_err().to_string();
        assert!(e.starts_with("invalid u0: -1 m/s is out of range"), "{e}");
        let p = pulse(None, &text(&[("r", "1cm")]), Spelling::Keyword).unwrap();
        let e = p.field(&p.contact()).unwrap_err().to_string();
        assert!(e.starts_with("invalid r: "), "{e}");
    }

    #[test]
    fn forcing_rows_apply_and_the_alias_names_itself() {
        let d = design(
            Design::default(),
            &text(&[
                ("force", "2N"),
                ("freq", "5Hz"),
                ("ball-position", "-1cm"),
                ("periods", "1e1"),
                ("ball-velocity", "0.5"),
            ]),
            Spelling::Flag,
        )
        .unwrap();
        let p = &d.damper;
        assert_eq!(
            (p.force_n, p.freq_hz, p.ball_position_m, p.ball_velocity_m_s, p.steady_periods),
            (2.0, 5.0, -0.01, 0.5, 10)
        );
        let on = design(Design::default(), &[("settle".into(), Input::Switch(true))], Spelling::Keyword).unwrap();
        assert!(on.damper.settle);
        let e = err(design(Design::default(), &text(&[("force-amplitude", "-1"), ("freq", "5")]), Spelling::Flag));
        assert!(e.starts_with("invalid --force-amplitude: -1 N is out of range"), "{e}");
        let e = err(design(Design::default(), &text(&[("force", "1")]), Spelling::Flag));
        assert_eq!(e, "invalid --freq: a force needs a frequency; give --freq (Hz)");
        let e = err(design(Design::default(), &[("periods".into(), Input::Num(2.5))], Spelling::Keyword));
        assert!(e.starts_with("invalid periods: '2.5' is not a whole number"), "{e}");
        let e = err(design(Design::default(), &text(&[("ball-position", "2.5cm")]), Spelling::Flag));
        assert!(e.starts_with("invalid --ball-position: ") && e.contains("d/2"), "{e}");
        let both = [("force".into(), Input::Num(1.0)), ("force_amplitude".into(), Input::Num(2.0))];
        assert_eq!(err(design(Design::default(), &both, Spelling::Keyword)), "invalid force_amplitude: is given twice");
    }

    #[test]
    fn a_response_design_starts_at_rest_and_needs_a_force() {
        let d = response_design(Design::paper_fig9(), &text(&[("force", "1")]), Spelling::Flag, 4.0, "force").unwrap();
        assert_eq!((d.damper.freq_hz, d.damper.v0_m_s), (4.0, 0.0));
        let kept = response_design(
            Design::paper_fig9(),
            &text(&[("force", "1"), ("ball-velocity", "0")]),
            Spelling::Flag,
            4.0,
            "force",
        );
        assert_eq!(kept.unwrap().damper.v0_m_s, Design::paper_fig9().damper.v0_m_s, "a typed start keeps v0");
        let e =
            response_design(Design::default(), &[], Spelling::Flag, 4.0, "force-amplitude").unwrap_err().to_string();
        assert_eq!(e, "invalid --force-amplitude: 0 N: a response needs a force; give --force-amplitude F0 (N)");
        let e = response_design(
            Design::default(),
            &text(&[("force", "1"), ("freq", "5Hz")]),
            Spelling::Keyword,
            4.0,
            "force",
        );
        assert!(e.unwrap_err().to_string().starts_with("invalid freq: '5Hz': a response sweeps the frequency"));
        assert!(check_ensemble(1, true, Spelling::Flag).is_ok() && check_ensemble(4, false, Spelling::Flag).is_ok());
        let e = check_ensemble(4, true, Spelling::Keyword).unwrap_err().to_string();
        assert!(e.starts_with("invalid ball_position: cannot be combined with ensemble 4"), "{e}");
    }

    #[test]
    fn a_response_without_frequencies_spans_the_default_band_of_the_design_given() {
        let given = text(&[("force", "1"), ("k", "2000"), ("main-mass", "2kg")]);
        let (d, freqs) = response_setup(Design::default(), &given, Spelling::Flag, None, "force").unwrap();
        // √(K/M − (C/2M)²)/2π with K 2000 N/m, M 2 kg, C 0.05 N·s/m (the default's).
        let f = (1000.0f64 - (0.05f64 / 4.0).powi(2)).sqrt() / (2.0 * std::f64::consts::PI);
        assert_eq!(freqs.len(), crate::response::DEFAULT_POINTS);
        assert!((freqs[0] - 0.6 * f).abs() < 1e-12 && (freqs[freqs.len() - 1] - 1.6 * f).abs() < 1e-12);
        assert_eq!(d.damper.freq_hz, freqs[0]);
        let (_, given_freqs) =
            response_setup(Design::default(), &given, Spelling::Flag, Some(vec![4.0, 5.0]), "force").unwrap();
        assert_eq!(given_freqs, [4.0, 5.0]);
        let e = response_setup(Design::default(), &text(&[("force", "1"), ("k", "-1")]), Spelling::Flag, None, "force");
        assert!(e.unwrap_err().to_string().starts_with("invalid --k: -1 N/m is out of range"));
    }

    #[test]
    fn names_are_checked_one_by_one_and_the_nearest_is_found() {
        assert!(check_named(&text(&[("force", "1"), ("plate", "steel")]), Spelling::Flag).is_ok(), "no relations");
        let e = check_named(&text(&[("gap", "1000m")]), Spelling::Flag).unwrap_err().to_string();
        assert!(e.starts_with("invalid --gap: 1000 m is out of range"), "{e}");
        assert_eq!(nearest_design_param("main_mas"), Some("main-mass"));
        assert_eq!(nearest_design_param("force-amplitud"), Some("force-amplitude"));
    }

    #[test]
    fn edit_distance_counts_edits() {
        assert_eq!(edit_distance("mas", "mass"), 1);
        assert_eq!(edit_distance("gap", "gap"), 0);
        assert_eq!(edit_distance("estar", "e-star"), 1);
    }
}
