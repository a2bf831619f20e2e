//! Parameters by name: the one mapping from named inputs — the command line's long flags
//! (`--main-mass 0.5`) and Python's keywords (`main_mass=0.5`) — to a checked design
//! ([`ValidDesign`](crate::design::ValidDesign)) or a single impact ([`PulseInput`]). Every number is checked against its range in
//! [`crate::limits`] (the one range table), so every front end accepts and refuses the same
//! values with the same one-line message.
//!
//! A front end hands in `(name, Input)` pairs, names as [`Spelling::key`] spells them: the long
//! flags without dashes (`main-mass`) from the command line, keywords (`main_mass`) from Python.
//! The one table [`PARAMS`] lists the known names, each row saying where it applies
//! ([`Where`]: a design, a single impact, or both); [`DESIGN`] and [`PULSE`] are its two views.
//! Values are parsed and applied in table order (not the order given), so every front end
//! reports the same first problem. Messages name the parameter the way the front end's user
//! typed it ([`Spelling`]): `invalid --main-mass: …` on the command line, `invalid main_mass: …`
//! in Python.
//!
//! Adding a parameter is one row in [`PARAMS`]: its name, what it accepts (a quantity of a
//! [`Kind`] inside a [`Range`], a choice of names, a name or a switch), where its value goes in
//! the one draft ([`DesignDraft`]) and where it applies. The command line's flags (its help,
//! completions and man page) for the design commands and `thud pulse`, Python's keywords, the
//! config file's keys, the explorer's fields and `thud limits` are then built from the row.

use crate::acoustics::{PulseShape, QuadSigns, Source};
use crate::design::{Design, Model};
use crate::limits::{short, Range};
use crate::units::Kind;

mod ball;
mod design;
mod given;
mod pulse;
#[cfg(test)]
mod tests;

pub use ball::follow_material;
use ball::{base_ball_of, resolve_ball, BallGiven};
pub use design::*;
pub use given::{check_ends, parse_range};
use given::{edit_distance, physical_conflicts, Given};
pub use pulse::*;

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

/// Where a row of [`PARAMS`] applies: to a design (`simulate`, `sweep`, …, the explorer, the
/// config file), to a single impact (`thud pulse`, Python's `pulse`), or to both. The views
/// [`DESIGN`] and [`PULSE`] are the rows of each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Where {
    Design,
    Impact,
    Both,
}

impl Where {
    /// Whether a row of this reach is a design's ([`DESIGN`]).
    pub const fn design(self) -> bool {
        matches!(self, Where::Design | Where::Both)
    }

    /// Whether a row of this reach is an impact's ([`PULSE`]).
    pub const fn impact(self) -> bool {
        matches!(self, Where::Impact | Where::Both)
    }
}

/// How a row reads for a single impact ([`PULSE`]) where it differs from a design's: its help
/// (an impact's defaults are Fig 2's, not a design's; empty: the row's help) and its relations
/// (an impact takes a plate without a sphere, on the paper's acrylic one).
#[derive(Debug, Clone, Copy)]
pub struct ImpactSide {
    pub help: &'static str,
    pub conflicts: Option<Conflict>,
    pub requires: Option<&'static str>,
}

/// One named parameter: one row of the table [`PARAMS`], from which every front end takes its
/// flag, keyword, field, help, range and check.
pub struct Param<T: 'static> {
    /// The parameter's name: the long flag without dashes (`main-mass`), the keyword with
    /// underscores; the force amplitude `force` is the exception on the command line, whose
    /// flag is its alias.
    pub name: &'static str,
    /// Another name a front end may hand the parameter in under (`force-amplitude` for `force`:
    /// the command line's flag, since its `--force` replaces a file; Python takes both);
    /// messages then name it as given.
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
    /// shows as the current or default value; for a choice that sets the design alone, the
    /// index of its name.
    pub get: Option<fn(&Design) -> f64>,
    /// Whether a design holds the row's value (None: every design does): K_HZ is not a design's
    /// own when its materials set it, nor a frequency without a force. [`check_design`] checks
    /// the value against the row's range wherever the row applies.
    pub applies: Option<fn(&Design) -> bool>,
    /// Where the row applies: a design, an impact or both ([`Where`]).
    pub used_in: Where,
    /// The row as an impact reads it ([`ImpactSide`]).
    pub impact: ImpactSide,
    /// The one model the row means something in, and why (None: both): given under the other,
    /// it is refused, not ignored.
    pub only_in: Option<(Model, &'static str)>,
}

// By hand: a derive would ask `T: Copy`, and a row holds only functions of `T`.
impl<T> Clone for Param<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for Param<T> {}

impl<T> Clone for Accepts<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for Accepts<T> {}

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
            used_in: Where::Design,
            impact: ImpactSide { help: "", conflicts: None, requires: None },
            only_in: None,
        }
    }

    /// The row meaning something in the model `model` only, for the reason `why`.
    const fn only_in(mut self, model: Model, why: &'static str) -> Self {
        self.only_in = Some((model, why));
        self
    }

    /// The row applying to a single impact too, with the impact's help `help` (empty: the
    /// row's) and no relation ([`ImpactSide`]).
    const fn both(mut self, help: &'static str) -> Self {
        self.used_in = Where::Both;
        self.impact.help = help;
        self
    }

    /// The row applying to a single impact only.
    const fn impact_only(mut self) -> Self {
        self.used_in = Where::Impact;
        self
    }

    /// The row as an impact reads it: its impact help and relations in place of a design's.
    const fn as_impact(mut self) -> Self {
        if !self.impact.help.is_empty() {
            self.help = self.impact.help;
        }
        self.conflicts = self.impact.conflicts;
        self.requires = self.impact.requires;
        self
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

/// The ranges `thud limits` lists: the range table's ([`crate::limits::RANGES`]), then the
/// range of any row of [`PARAMS`] it lacks (a row may hold its range itself), in table order.
pub fn listed_ranges() -> Vec<&'static Range> {
    let table: &'static [Range] = &crate::limits::RANGES;
    let mut out: Vec<&'static Range> = table.iter().collect();
    for r in PARAMS.iter().filter_map(Param::range) {
        if !out.iter().any(|o| o.param == r.param) {
            out.push(r);
        }
    }
    out
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

/// The help of the air-temperature row.
const AIR_TEMPERATURE_HELP: &str = "Air temperature (°C) of the physical model: ρ0 and c follow [default: 20]";
/// The help of the air-pressure row.
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
