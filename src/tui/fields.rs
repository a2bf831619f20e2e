// Over 800 lines: the field table and its units, steps and typing stay together so every row behaves alike.
//! The editable parameters of the panel: how each one is shown (display units), stepped and
//! typed. Values live in the `Design` in SI units; conversions happen only here, at the edge.
//! The knobs turn a [`Tunable`]: a design alone, or a [`Setup`] (a design and the explorer's
//! ensemble size N, which is not part of a design: the command line's `--ensemble`).
//!
//! A field is made one way: a row of the engine's table ([`params::DESIGN`]: its name, label,
//! help, unit, range, group and accessor) seen through a [`Look`], the explorer's own columns
//! (a unit such as g for the mass, digits, a step, a word for a value). A row without a look
//! in `LOOKS` is a field with the row's defaults, so a new row needs no line here; the one
//! look without a row is the explorer's own field, the ensemble size N.

use std::fmt;

use super::compute;
use crate::contact::MATERIALS;
use crate::damper::Solver;
use crate::design::{Design, Materials};
use crate::error::ThudError;
use crate::limits;
use crate::params::{self, Accepts, Group, DESIGN};
use crate::units::{self, sig, Kind};

/// One field of the panel (a row of it): its place in [`Knob::ALL`], made from a row of the
/// engine's table and its [`Look`].
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Knob(usize);

impl fmt::Debug for Knob {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Knob({})", self.param())
    }
}

/// How the panel writes a number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    /// This many significant digits, then the unit shown (`40.50 g`; bare without a unit).
    Sig(usize),
    /// Scientific notation with this many decimals, no unit (`3.456e9`).
    Sci(usize),
    /// A whole number, bare (`10`).
    Whole,
    /// A whole number and the unit shown (`12 runs`).
    WholeUnit,
}

/// A design's valid range for a field (internal units): lowest, highest.
type Bounds = fn(&Design) -> (f64, f64);
/// Sets a field from typed text.
type Parse = fn(&mut Design, &str) -> Result<(), ThudError>;

/// The explorer's columns for a field, beside its row of [`params::DESIGN`]: each one empty
/// (or `None`) takes the row's default, so a row needs a look only where the panel shows or
/// edits it otherwise than the row says. The hooks (`get` … `cycled`) are for the few fields
/// that hold more than one number: K_HZ (which the materials may set), the materials and the
/// solver (two rows each), the source (θ follows its open side).
#[derive(Clone, Copy)]
pub struct Look {
    /// The rows of [`params::DESIGN`] the field sets, its own (where the panel lists it) first;
    /// none for the explorer's own field, the ensemble size N of a [`Setup`].
    rows: &'static [&'static str],
    /// The panel's label (empty: the row's).
    label: &'static str,
    /// The name in messages, the tour's key and the `/` filter (empty: the row's).
    name: &'static str,
    /// What it is, for the status line's hint (empty: the row's help).
    what: &'static str,
    /// The unit a value is shown and a plain number typed in (empty: the row's plain unit),
    /// and the factors to the internal unit and back (each exact as written: 1/1e-3 is not
    /// 1e3 in binary, and the panel has always multiplied by the one it shows with).
    unit: &'static str,
    to_internal: f64,
    to_shown: f64,
    /// How a number is written (None: 4 significant digits for a quantity, bare for a count).
    format: Option<Format>,
    /// The range of a field without a row (a row's field has the row's).
    range: Option<&'static limits::Range>,
    /// Values shown as words (a force of 0 is "0 (free decay)"); a step that ends within 1e-9
    /// of such a 0 is that 0, exactly.
    marks: &'static [(f64, &'static str)],
    /// A switch's word when on (empty: "on").
    on: &'static str,
    /// Words typed for a choice or a switch beyond its names, each with the index it means.
    words: &'static [(&'static str, usize)],
    /// Whether a choice takes the first name the typed text begins (`dip` for dipole).
    prefix: bool,
    /// Whether the ball follows its material after a change (the one ball rule,
    /// [`params::follow_material`]).
    follows: bool,
    /// How it steps (None: from the row: a ratio for a range above 0, ± otherwise, a count
    /// doubled or halved, a choice cycled).
    step: Option<Stepping>,
    /// What a change recomputes (None: from the row's group).
    scope: Option<Scope>,
    /// The valid range of a design in internal units, where it depends on the design (None:
    /// the row's range).
    bounds: Option<Bounds>,
    /// The value, where the row's accessor does not give it as the panel shows it.
    get: Option<fn(&Design) -> f64>,
    /// Sets the value, where more than the row's value changes.
    set: Option<fn(&mut Design, f64)>,
    /// The value as shown, for a field of several rows.
    show: Option<fn(&Design) -> String>,
    /// Moves a field of several rows to its next (`true`) or previous choice.
    cycle: Option<fn(&mut Design, bool)>,
    /// Sets a field of several rows from typed text.
    parse: Option<Parse>,
    /// What follows any change of the field (a force switched on gets its frequency).
    then: Option<fn(&mut Design)>,
    /// What follows a cycle of the field (θ back inside the new source's open side).
    cycled: Option<fn(&mut Design)>,
    /// Where a ratio step starts from 0 (a forcing frequency, 0 while no force).
    start: Option<fn(&Design) -> f64>,
    /// Why the design does not use the field now (the air in the paper's model), if it does not.
    idle: Option<fn(&Design) -> Option<&'static str>>,
}

impl Look {
    /// The look of a field setting `rows` (the row's defaults in every column).
    const fn of(rows: &'static [&'static str]) -> Self {
        Look {
            rows,
            label: "",
            name: "",
            what: "",
            unit: "",
            to_internal: 1.0,
            to_shown: 1.0,
            format: None,
            range: None,
            marks: &[],
            on: "",
            words: &[],
            prefix: false,
            follows: false,
            step: None,
            scope: None,
            bounds: None,
            get: None,
            set: None,
            show: None,
            cycle: None,
            parse: None,
            then: None,
            cycled: None,
            start: None,
            idle: None,
        }
    }

    /// The field of the one row `rows`, labelled `label`, explained by `what`.
    const fn row(rows: &'static [&'static str], label: &'static str, what: &'static str) -> Self {
        let mut look = Look::of(rows);
        look.label = label;
        look.what = what;
        look
    }

    const fn name(mut self, name: &'static str) -> Self {
        self.name = name;
        self
    }

    /// Shown and typed in `unit`, `to_internal` of the internal unit (and `to_shown` back).
    const fn unit(mut self, unit: &'static str, to_internal: f64, to_shown: f64) -> Self {
        self.unit = unit;
        self.to_internal = to_internal;
        self.to_shown = to_shown;
        self
    }

    /// Shown with `n` significant digits.
    const fn digits(mut self, n: usize) -> Self {
        self.format = Some(Format::Sig(n));
        self
    }

    const fn format(mut self, format: Format) -> Self {
        self.format = Some(format);
        self
    }

    const fn marks(mut self, marks: &'static [(f64, &'static str)]) -> Self {
        self.marks = marks;
        self
    }

    const fn words(mut self, words: &'static [(&'static str, usize)]) -> Self {
        self.words = words;
        self
    }

    const fn step(mut self, step: Stepping) -> Self {
        self.step = Some(step);
        self
    }

    const fn scope(mut self, scope: Scope) -> Self {
        self.scope = Some(scope);
        self
    }
}

/// The explorer's looks at the rows of [`params::DESIGN`] (in table order), and its own field.
/// Every other row is a field with the row's defaults.
#[rustfmt::skip]
const LOOKS: &[Look] = &[
    Look::row(&["mass"], "mass m", "the ball (impact mass) rattling in the enclosure")
        .unit("g", 1e-3, 1e3).digits(4).step(Stepping::Add(1e-3, 1e-4)).scope(Scope::Design),
    Look::row(&["gap"], "gap d", "total clearance of the ball in its enclosure (d/2 each side)")
        .unit("cm", 1e-2, 1e2).digits(3).step(Stepping::Add(2e-3, 2e-4)).scope(Scope::Design),
    Look::row(&["v0"], "v0", "initial speed of the main mass, the blow that starts the ring-down (Eq 25)")
        .digits(3).step(Stepping::Add(0.1, 0.01)),
    Look::row(&["main-mass"], "M", "the structure being damped (Eq 25)").digits(3).step(Stepping::Add(0.05, 0.005)),
    Look::row(&["k"], "K", "stiffness of the structure's spring (Eq 25)").digits(4).step(Stepping::Mul(0.1, 0.01)),
    Look::row(&["c"], "C", "viscous damping of the structure (Eq 25)").digits(3).step(Stepping::Mul(0.1, 0.01)),
    Look::row(&["c1"], "c1", "contact damping in the Hertz contact force (Eq 26)").digits(4).step(Stepping::Mul(0.1, 0.01)),
    // Shows the K_HZ the materials give; a K_HZ typed switches the materials off.
    Look {
        get: Some(|d| d.hertz_stiffness().unwrap_or(d.damper.k_hz)),
        set: Some(|d, v| {
            d.damper.k_hz = v;
            d.materials = None;
        }),
        ..Look::row(&["k-hz"], "K_HZ", "Hertz contact stiffness, force K_HZ·δ^1.5 (Eqs 1, 26)")
            .format(Format::Sci(3)).step(Stepping::Mul(0.1, 0.01))
    },
    Look {
        show: Some(show_materials),
        cycle: Some(cycle_materials),
        parse: Some(parse_materials),
        ..Look::row(&["sphere", "plate"], "materials", "ball/plate materials giving K_HZ (Eq 2); off uses the K_HZ typed")
            .name("materials")
    },
    Look { on: "no tension", ..Look::row(&["no-tension"], "clamp", "no tension: the contact force may not pull (Eq 26 clamped at ≥ 0)")
        .words(&[("no tension", 1), ("no-tension", 1)]) },
    Look::row(&["duration"], "duration", "simulated time of the ring-down").digits(3).step(Stepping::Add(0.5, 0.1)),
    Look {
        show: Some(show_solver),
        cycle: Some(cycle_solver),
        parse: Some(parse_solver),
        ..Look::row(&["solver", "dt"], "solver", "event-driven (exact flight) or the paper's Newmark-β at a fixed step")
    },
    Look::row(&["r"], "r", "distance of the listener from the contact point").digits(3).step(Stepping::Add(0.05, 0.01)),
    Look {
        bounds: Some(|d| {
            let r = limits::theta_deg(d.radiation.source);
            (r.min, r.max)
        }),
        ..Look::row(&["theta"], "θ", "listener angle from the plate's normal (0 = along the normal)")
            .digits(3).step(Stepping::Add(5.0, 1.0))
    },
    Look { prefix: true, cycled: Some(clamp_theta), ..Look::row(&["source"], "source",
        "reflecting surfaces: single (free ball), dipole (plate), quadrupole (wall–floor corner)") },
    Look::row(&["quad-signs"], "quad signs", "corner wall images: rigid wall, or the paper's signs (a pressure-release wall)"),
    Look::row(&["pulse"], "pulse", "contact acceleration: the paper's half-sine (Eq 7) or the exact Hertz pulse")
        .words(&[("halfsine", 0), ("sine", 0), ("half sine", 0), ("exact", 1)]),
    Look { follows: true, ..Look::of(&["model"]) },
    Look { idle: Some(paper_air), ..Look::of(&["air-temperature"]) },
    Look { idle: Some(paper_air), ..Look::of(&["air-pressure"]) },
    Look { idle: Some(physical_air), ..Look::of(&["rho-c"]) },
    Look { idle: Some(physical_air), ..Look::of(&["sound-speed"]) },
    Look::row(&["l-star"], "L*", "zone threshold on SPLmax: below L* is quiet")
        .name("L*").digits(4).step(Stepping::Add(1.0, 0.1)),
    Look::row(&["e-star"], "e*", "zone threshold on the damping inclination: e ≥ e* is strong")
        .name("e*").digits(3).step(Stepping::Add(0.1, 0.01)),
    Look {
        then: Some(force_frequency),
        ..Look::row(&["force"], "force F0", "harmonic force F0·cos(2πft) on the main mass (Eq 25 forced); 0 is the paper's free decay, > 0 adds the steady-state readout and the response view (f)")
            .digits(3).marks(&[(0.0, "0 (free decay)")]).step(Stepping::Add(0.1, 0.01))
    },
    Look {
        start: Some(start_frequency_hz),
        ..Look::row(&["freq"], "freq f", "forcing frequency f; moves the marker on the response curve (f view) without recomputing it; a force switched on starts at the natural frequency")
            .digits(4).marks(&[(0.0, "— (no force)")]).step(Stepping::Mul(0.02, 0.002))
    },
    Look {
        bounds: Some(|d| (-0.5 * d.damper.gap_m, 0.5 * d.damper.gap_m)),
        ..Look::row(&["ball-position"], "ball y0", "the ball's start offset from the enclosure's centre, |y0| < d/2 (0: centred, as the paper)")
            .unit("cm", 1e-2, 1e2).digits(3).marks(&[(0.0, "0 (centred)")]).step(Stepping::Add(1e-3, 1e-4))
    },
    // The explorer's own field: the ensemble size N of a [`Setup`], no row of a design.
    Look {
        range: Some(&limits::ENSEMBLE),
        ..Look::row(&[], "ensemble N", "runs from N ball offsets spread over the clearance (y0 = −d/2 + (k + ½)·d/N): the readout shows median [p10–p90], the chart shades cells where < 70 % of runs agree")
            .name("ensemble").unit("runs", 1.0, 1.0).format(Format::WholeUnit).marks(&[(1.0, "1 (single run)")])
            .step(Stepping::Count).scope(Scope::All)
    },
];

/// The air's temperature and pressure do nothing in the paper's model (its air is the
/// paper's ρ0c and c); the physical model takes its air from them.
fn paper_air(d: &Design) -> Option<&'static str> {
    (d.model == crate::design::Model::Paper)
        .then_some("unused by the paper's model (its air is ρ0c and c as set); model physical uses it")
}

/// The paper model's air (ρ0c and c) does nothing in the physical model, which takes its air
/// from the temperature and pressure.
fn physical_air(d: &Design) -> Option<&'static str> {
    (d.model == crate::design::Model::Physical)
        .then_some("unused by the physical model (its air follows from air T and air p); model paper uses it")
}

/// The row of [`params::DESIGN`] called `name` (its index; the table's length if none).
const fn design_row(name: &str) -> usize {
    let mut i = 0;
    while i < DESIGN.len() && !params::same_name(DESIGN[i].name, name) {
        i += 1;
    }
    i
}

/// One entry of [`FIELDS`]: the index of the field's own row in [`params::DESIGN`]
/// (`DESIGN.len()` for the explorer's own field) and its look.
#[derive(Clone, Copy)]
struct Field {
    row: usize,
    look: Look,
}

/// The look whose rows include `name`: as its own (first) row, or (`later`) after it.
const fn look_at(name: &str, later: bool) -> Option<Look> {
    let mut l = 0;
    while l < LOOKS.len() {
        let rows = LOOKS[l].rows;
        let mut r = 0;
        while r < rows.len() {
            if (r > 0) == later && params::same_name(rows[r], name) {
                return Some(LOOKS[l]);
            }
            r += 1;
        }
        l += 1;
    }
    None
}

/// Whether the row `i` of [`params::DESIGN`] is a later row of a look (`plate`, `dt`): set by
/// the field of its first row, with no field of its own.
const fn later_row(i: usize) -> bool {
    look_at(DESIGN[i].name, true).is_some()
}

/// How many fields there are: a field for every row but the later rows of a look, and the
/// looks without a row.
const FIELD_COUNT: usize = {
    let mut n = 0;
    let mut i = 0;
    while i < DESIGN.len() {
        if !later_row(i) {
            n += 1;
        }
        i += 1;
    }
    let mut l = 0;
    while l < LOOKS.len() {
        if LOOKS[l].rows.is_empty() {
            n += 1;
        }
        l += 1;
    }
    n
};

/// Every field, grouped as the engine's table groups its rows ([`Group::ALL`] order: design,
/// forcing, listener, solver, study) and in table order inside a group, each the row's look
/// (or the row's defaults); the explorer's own fields last, in the study group.
const FIELDS: [Field; FIELD_COUNT] = {
    // Every look's rows are rows of the table (a look of a renamed row would be lost).
    let mut l = 0;
    while l < LOOKS.len() {
        let mut r = 0;
        while r < LOOKS[l].rows.len() {
            assert!(design_row(LOOKS[l].rows[r]) < DESIGN.len(), "a look names a row DESIGN lacks");
            r += 1;
        }
        l += 1;
    }
    let mut all = [Field { row: DESIGN.len(), look: Look::of(&[]) }; FIELD_COUNT];
    let mut k = 0;
    let mut g = 0;
    while g < Group::ALL.len() {
        let mut i = 0;
        while i < DESIGN.len() {
            if DESIGN[i].group as usize == Group::ALL[g] as usize && !later_row(i) {
                let look = match look_at(DESIGN[i].name, false) {
                    Some(look) => look,
                    None => Look::of(std::slice::from_ref(&DESIGN[i].name)),
                };
                all[k] = Field { row: i, look };
                k += 1;
            }
            i += 1;
        }
        g += 1;
    }
    let mut l = 0;
    while l < LOOKS.len() {
        if LOOKS[l].rows.is_empty() {
            all[k] = Field { row: DESIGN.len(), look: LOOKS[l] };
            k += 1;
        }
        l += 1;
    }
    all
};

/// What the knobs turn: a design, or a design with the explorer's ensemble size.
pub trait Tunable: Clone {
    fn design(&self) -> &Design;
    fn design_mut(&mut self) -> &mut Design;
    /// Runs per design N (1 for a design alone: the single trajectory).
    fn runs(&self) -> usize;
    /// Sets N; false if this has no ensemble size (a design alone).
    fn set_runs(&mut self, n: usize) -> bool;
}

impl Tunable for Design {
    fn design(&self) -> &Design {
        self
    }

    fn design_mut(&mut self) -> &mut Design {
        self
    }

    fn runs(&self) -> usize {
        1
    }

    fn set_runs(&mut self, _: usize) -> bool {
        false
    }
}

/// Checks a setup that was loaded rather than typed (a saved design, a preset, a tour step)
/// as if each of its fields had been typed: every field's range, the work caps (named as the
/// duration, the field that usually carries them: a 1e6-s design is refused with the chart's
/// cap line, as typing 1e6 is), the whole-design checks and the engine's validation.
pub fn check_loaded<S: Tunable>(s: &S) -> Result<(), ThudError> {
    // The forcing and the ball's start only where they apply: the whole-design check has them.
    for k in Knob::ALL.into_iter().filter(|k| ![Knob::FORCE, Knob::FREQ, Knob::BALL_POSITION].contains(k)) {
        k.check_range(s)?;
    }
    params::check_design(s.design())?;
    Knob::DURATION.checked(s.clone()).map(drop)
}

/// What the explorer runs: the design and the ensemble size N (runs from N ball offsets spread
/// over the clearance, [`crate::ensemble`]; 1 is the single trajectory).
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    pub design: Design,
    pub runs: usize,
}

impl Tunable for Setup {
    fn design(&self) -> &Design {
        &self.design
    }

    fn design_mut(&mut self) -> &mut Design {
        &mut self.design
    }

    fn runs(&self) -> usize {
        self.runs
    }

    fn set_runs(&mut self, n: usize) -> bool {
        self.runs = n;
        true
    }
}

/// What kind of change a field takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stepping {
    /// Add ± coarse or ± fine (internal units).
    Add(f64, f64),
    /// Multiply or divide by (1 + coarse) or (1 + fine).
    Mul(f64, f64),
    /// Cycle through choices.
    Cycle,
    /// A count: double or halve (coarse), or ± 1 (fine).
    Count,
}

/// Which recomputation a change of this field needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Only the sound at the observer (and the chart's levels).
    Acoustics,
    /// This one design (mass or gap): re-simulate it, the chart stays.
    Design,
    /// Everything shared by all cells: re-simulate and re-sweep.
    All,
    /// Only the zone thresholds: no physics at all.
    Thresholds,
}

/// Newmark step used when the solver is switched to Newmark in the explorer (s). Coarser than
/// the paper's 1e-7 s so the run stays interactive; type e.g. "1e-7" to change it.
pub const TUI_NEWMARK_DT_S: f64 = 1e-6;

impl Knob {
    /// All fields, in panel order: grouped as the engine's table groups its rows, in table
    /// order inside a group, the ensemble size last.
    pub const ALL: [Knob; FIELD_COUNT] = {
        let mut all = [Knob(0); FIELD_COUNT];
        let mut i = 0;
        while i < FIELD_COUNT {
            all[i] = Knob(i);
            i += 1;
        }
        all
    };

    /// The fields the explorer names in its code (keys, messages, tests), by their names.
    pub const MASS: Knob = Knob::named("mass");
    pub const GAP: Knob = Knob::named("gap");
    pub const R: Knob = Knob::named("r");
    pub const THETA: Knob = Knob::named("theta");
    pub const V0: Knob = Knob::named("v0");
    pub const K: Knob = Knob::named("k");
    pub const C1: Knob = Knob::named("c1");
    pub const MATERIALS: Knob = Knob::named("materials");
    pub const SOURCE: Knob = Knob::named("source");
    pub const SOLVER: Knob = Knob::named("solver");
    pub const DURATION: Knob = Knob::named("duration");
    pub const L_STAR: Knob = Knob::named("L*");
    pub const E_STAR: Knob = Knob::named("e*");
    pub const FORCE: Knob = Knob::named("force");
    pub const FREQ: Knob = Knob::named("freq");
    pub const BALL_POSITION: Knob = Knob::named("ball-position");
    pub const RUNS: Knob = Knob::named("ensemble");

    /// The field called `name` ([`Knob::param`]), at compile time: no such field is a build
    /// error where a constant names it.
    pub const fn named(name: &str) -> Knob {
        let mut i = 0;
        while i < FIELD_COUNT {
            if params::same_name(Knob(i).param(), name) {
                return Knob(i);
            }
            i += 1;
        }
        panic!("no explorer field of that name")
    }

    /// The field's entry of [`FIELDS`].
    const fn field(self) -> Field {
        FIELDS[self.0]
    }

    const fn look(self) -> Look {
        self.field().look
    }

    /// The rows of the engine's table ([`params::DESIGN`]) this field sets (none for the
    /// ensemble size, which is the explorer's, not a design's).
    pub fn rows(self) -> &'static [&'static str] {
        self.look().rows
    }

    /// Whether the field is its row alone, shown with the row's defaults (no look of the
    /// explorer's): a row added to the table becomes such a field.
    pub fn plain(self) -> bool {
        self.rows().first().is_some_and(|own| !LOOKS.iter().any(|l| l.rows.first() == Some(own)))
    }

    /// The group the field is listed under: its first row's in the engine's table; the
    /// ensemble size N (the explorer's own) with the study.
    pub fn group(self) -> Group {
        DESIGN.get(self.field().row).map_or(Group::Study, |p| p.group)
    }

    /// The engine's row of a field that sets exactly one.
    pub fn row(self) -> Option<&'static params::Param<params::DesignDraft>> {
        match self.rows() {
            [_] => DESIGN.get(self.field().row),
            _ => None,
        }
    }

    /// Short label for the panel: the look's, else the row's.
    pub fn label(self) -> &'static str {
        match (self.look().label, DESIGN.get(self.field().row)) {
            ("", Some(row)) => row.label,
            (label, _) => label,
        }
    }

    /// The parameter's name in messages (as on the command line): the look's, else the row's.
    pub const fn param(self) -> &'static str {
        match (self.look().name, self.field().row) {
            (name, _) if !name.is_empty() => name,
            (_, i) if i < DESIGN.len() => DESIGN[i].name,
            _ => "?",
        }
    }

    /// What the field is, for the status line's hint: the look's words, else the row's help.
    pub fn what(self) -> &'static str {
        match (self.look().what, DESIGN.get(self.field().row)) {
            ("", Some(row)) => row.help,
            (what, _) => what,
        }
    }

    /// The unit a typed plain number is read in, and the unit the value is shown in.
    pub fn kind(self) -> Option<Kind> {
        match self.row()?.accepts {
            Accepts::Quantity { kind, .. } => Some(kind),
            _ => None,
        }
    }

    /// The field's valid range: its row's in the engine's table ([`params::DESIGN`], whose
    /// ranges are [`crate::limits`]'s); the ensemble size's is [`limits::ENSEMBLE`].
    pub fn range(self) -> Option<limits::Range> {
        match self.look().range {
            Some(range) => Some(*range),
            None => self.row()?.range().copied(),
        }
    }

    /// The unit the value is shown in, and the factor from it to the internal unit (SI;
    /// degrees; dB; cm/s): a typed plain number is read in this unit (`45` for the mass is
    /// 45 g, as shown), not in the internal one.
    pub fn display_unit(self) -> Option<(&'static str, f64)> {
        let look = self.look();
        let plain = match self.row().map(|r| &r.accepts) {
            Some(Accepts::Quantity { kind, .. }) => kind.plain_unit(),
            Some(Accepts::Count { range, .. }) => range.unit,
            None if look.range.is_some() => "",
            _ => return None,
        };
        Some((if look.unit.is_empty() { plain } else { look.unit }, look.to_internal))
    }

    /// The valid range in the display unit: (lowest, highest). θ's is the current source's
    /// open side; y0's is inside the clearance, −d/2 to d/2 (both excluded).
    pub fn display_range(self, d: &Design) -> Option<(f64, f64)> {
        let (_, k) = self.display_unit()?;
        let (lo, hi) = match self.look().bounds {
            Some(bounds) => bounds(d),
            None => self.range().map(|r| (r.min, r.max))?,
        };
        Some((lo / k, hi / k))
    }

    /// Refuses a design whose runs in the explorer would exceed the work caps the command line
    /// uses ([`limits::design_run`] for the live design, [`limits::sweep_work`] for the chart's
    /// fine grid, and with N > 1 [`limits::ensemble_work`] for the live design's N runs and
    /// the chart's N runs a cell): the same estimates and limits, worded for the status line.
    /// This is what keeps a duration, a Newmark step or an ensemble typed here from running
    /// for hours or out of memory.
    fn check_work<S: Tunable>(self, s: &S) -> Result<(), ThudError> {
        // A design that fails its checks has no work to estimate: the checks after this one
        // ([`Design::check`] in [`Knob::checked`]) refuse it.
        let Ok(d) = s.design().clone().check() else { return Ok(()) };
        let d = &d;
        let cells = compute::Grids::default().fine.len();
        let runs = s.runs();
        // The field just changed is the parameter "given": the engine's one decision of
        // which cap a run is over ([`limits::check_run`], [`limits::check_sweep`],
        // [`limits::check_runs`]); the status line names this field.
        let given = |n: &str| self.rows().contains(&n);
        let refused = limits::check_run(d, &given, compute::HISTORY_SAMPLES)
            .and_then(|()| limits::check_sweep(d, &given, cells, 1))
            .and_then(|()| if runs > 1 { limits::check_runs(d, &given, 1, runs) } else { Ok(()) })
            .and_then(|()| if runs > 1 { limits::check_runs(d, &given, cells, runs) } else { Ok(()) });
        match refused {
            Err(r) => {
                // Named by a later row of the field that the design uses, with its value (the
                // solver by its Newmark step, as the command line's --dt), else by the field.
                let later =
                    self.rows().iter().skip(1).filter_map(|n| params::design_param(n)).find_map(|p| {
                        p.get.filter(|_| p.applies.is_some_and(|applies| applies(d))).map(|get| (p, get(d)))
                    });
                let (name, shown) = match later {
                    Some((p, v)) => (p.name, format!("{} {}", limits::short(v), p.unit())),
                    None => (self.param(), self.display(s)),
                };
                Err(ThudError::invalid(name, format!("{shown}: {}", r.estimate.describe())))
            }
            Ok(()) => Ok(()),
        }
    }

    fn check_range<S: Tunable>(self, s: &S) -> Result<(), ThudError> {
        let d = s.design();
        if let (Some(r), Some(v), Some((unit, k))) = (self.range(), self.value(s), self.display_unit()) {
            if !r.contains(v) {
                let (lo, hi) = (r.min / k, r.max / k);
                let shown = if v.is_finite() { format!("{} {unit}", limits::short(v / k)) } else { format!("{v}") };
                return Err(ThudError::invalid(
                    self.param(),
                    format!(
                        "{shown} is out of range; the {} must be {} to {} {unit} ({})",
                        r.what,
                        limits::short(lo),
                        limits::short(hi),
                        r.reason
                    ),
                ));
            }
        }
        if let Solver::Newmark { dt_s } = d.solver {
            limits::DT.check(dt_s)?;
        }
        Ok(())
    }

    /// The checks every new value passes, in order: the field's own range (in the unit shown),
    /// the work caps, and the engine's check of the whole design ([`Design::check`]: the
    /// physics' own checks, then the one range table over the whole design, e.g. |y0| < d/2
    /// and a force's frequency, as the command line checks it), the check every job repeats.
    pub(crate) fn checked<S: Tunable>(self, next: S) -> Result<S, ThudError> {
        self.check_range(&next)?;
        self.check_work(&next)?;
        next.design().clone().check()?;
        Ok(next)
    }

    /// What a change of this field invalidates: the look's, else by the row's group (the
    /// listener's rows only the sound, the study's only the zones).
    pub fn scope(self) -> Scope {
        self.look().scope.unwrap_or(match self.group() {
            Group::Listener => Scope::Acoustics,
            Group::Study => Scope::Thresholds,
            _ => Scope::All,
        })
    }

    /// How the field is stepped: the look's, else by what its row accepts.
    pub fn step(self) -> Stepping {
        self.look().step.unwrap_or(match self.row().map(|p| &p.accepts) {
            Some(Accepts::Quantity { range, .. }) if range.min > 0.0 => Stepping::Mul(0.1, 0.01),
            Some(Accepts::Quantity { .. }) => Stepping::Add(0.1, 0.01),
            Some(Accepts::Count { .. }) => Stepping::Count,
            _ => Stepping::Cycle,
        })
    }

    /// The numeric value in internal units (SI; degrees; dB; cm/s), if the field is numeric
    /// and part of a design (the ensemble size is not: see [`Knob::value`]); none where the
    /// design does not use the row (a density while the radius is set).
    pub fn get(self, d: &Design) -> Option<f64> {
        if let Some(get) = self.look().get {
            return Some(get(d));
        }
        let row = self.row().filter(|r| matches!(r.accepts, Accepts::Quantity { .. } | Accepts::Count { .. }))?;
        Some((row.get?)(d)).filter(|v| !v.is_nan())
    }

    /// The numeric value of this field of `s` (internal units), the ensemble size included.
    pub fn value<S: Tunable>(self, s: &S) -> Option<f64> {
        if self.rows().is_empty() {
            return Some(s.runs() as f64);
        }
        self.get(s.design())
    }

    /// Sets the numeric value (internal units) on a copy; the ensemble size is refused by a
    /// design alone (it is the explorer's, not the design's).
    fn set<S: Tunable>(self, s: &S, v: f64) -> Result<S, ThudError> {
        let mut s = s.clone();
        if self.rows().is_empty() {
            // A count: rounded, and kept inside 1.. (the range check names a bad one).
            let n = if v.is_finite() && v >= 1.0 { v.round() as usize } else { 0 };
            if !s.set_runs(n) {
                return Err(ThudError::invalid(self.param(), "the ensemble size is the explorer's, not a design's"));
            }
            return Ok(s);
        }
        let d = s.design_mut();
        match (self.look().set, self.row()) {
            (Some(set), _) => set(d, v),
            (None, Some(row)) => *d = params::set_number(d, row, v),
            (None, None) => {}
        }
        Ok(s)
    }

    /// Why the design does not use the field now, if it does not (the air in the paper's model).
    pub fn idle(self, d: &Design) -> Option<&'static str> {
        self.look().idle.and_then(|why| why(d))
    }

    /// The value as the panel and the status line show it: [`Knob::display`], marked
    /// "(unused)" where the design does not use the field.
    pub fn shown<S: Tunable>(self, s: &S) -> String {
        let v = self.display(s);
        if self.idle(s.design()).is_some() {
            format!("{v} (unused)")
        } else {
            v
        }
    }

    /// The value as people read it: display units, a few significant digits; a word for a
    /// switch, a choice or a marked value; — where the design does not use the row.
    pub fn display<S: Tunable>(self, s: &S) -> String {
        let (d, look) = (s.design(), self.look());
        if let Some(show) = look.show {
            return show(d);
        }
        let read = || self.row().and_then(|r| r.get).map_or(f64::NAN, |get| get(d));
        match self.row().map(|r| &r.accepts) {
            Some(Accepts::Switch { .. }) if read() == 0.0 => "off".into(),
            Some(Accepts::Switch { .. }) => if look.on.is_empty() { "on" } else { look.on }.into(),
            Some(Accepts::Choice { names, .. }) => {
                let v = read();
                let name = if v.is_finite() { names.get(v as usize).copied() } else { None };
                name.unwrap_or("—").into()
            }
            _ => {
                let Some(v) = self.value(s) else { return "—".into() };
                if let Some((_, word)) = look.marks.iter().find(|(at, _)| *at == v) {
                    return (*word).into();
                }
                let unit = self.display_unit().map_or("", |(unit, _)| unit);
                match look.format.unwrap_or(if self.kind().is_some() { Format::Sig(4) } else { Format::Whole }) {
                    Format::Sig(n) if unit.is_empty() => sig(v * look.to_shown, n),
                    Format::Sig(n) => format!("{} {unit}", sig(v * look.to_shown, n)),
                    Format::Sci(n) => format!("{v:.n$e}"),
                    Format::Whole => format!("{}", v.round()),
                    Format::WholeUnit => format!("{} {unit}", v.round()),
                }
            }
        }
    }

    /// The design (or setup) with this field stepped once (`up`: increase), validated. A force
    /// stepped up from 0 while f is unset gets f at the structure's natural frequency (the
    /// engine's damped frequency of Eq 25), so that a force always has its frequency.
    pub fn stepped<S: Tunable>(self, s: &S, up: bool, fine: bool) -> Result<S, ThudError> {
        let look = self.look();
        let next = match (self.step(), self.value(s)) {
            (Stepping::Add(c, f), Some(v)) => {
                let st = if fine { f } else { c };
                // Snap to the step grid so repeated steps give round numbers.
                let n = (v / st).round() + if up { 1.0 } else { -1.0 };
                let v = if ((v / st) - (v / st).round()).abs() < 1e-6 { n * st } else { v + if up { st } else { -st } };
                // A step to (near) a 0 that has its own word (a force off) is that 0, exactly.
                let zero = v.abs() < 1e-9 && look.marks.iter().any(|(at, _)| *at == 0.0);
                self.set(s, if zero { 0.0 } else { v })?
            }
            (Stepping::Mul(c, f), Some(v)) => match look.start {
                Some(start) if v == 0.0 => self.set(s, start(s.design()))?,
                _ => {
                    let k = 1.0 + if fine { f } else { c };
                    self.set(s, if up { v * k } else { v / k })?
                }
            },
            (Stepping::Count, Some(v)) => {
                let n = v.round();
                let next = match (up, fine) {
                    (true, false) => 2.0 * n,
                    (false, false) => (n / 2.0).floor(),
                    (true, true) => n + 1.0,
                    (false, true) => n - 1.0,
                };
                self.set(s, next)?
            }
            _ => self.cycled(s, up),
        };
        self.checked(self.then(next))
    }

    /// `s` after a change of this field, with what the look says follows it.
    fn then<S: Tunable>(self, mut s: S) -> S {
        if let Some(then) = self.look().then {
            then(s.design_mut());
        }
        s
    }

    /// The design with a choice field moved to the next (`up`) or previous option: a switch
    /// toggled, a choice's next name (the look's own cycle for a field of several rows).
    fn cycled<S: Tunable>(self, s: &S, up: bool) -> S {
        let mut s = s.clone();
        let (d, look) = (s.design_mut(), self.look());
        if let Some(cycle) = look.cycle {
            cycle(d, up);
            return s;
        }
        let Some(row) = self.row() else { return s };
        match (&row.accepts, row.get) {
            (Accepts::Switch { .. }, Some(get)) => {
                let on = get(d) != 0.0;
                *d = params::set_number(d, row, if on { 0.0 } else { 1.0 });
            }
            // A choice that reads back its index: the next or previous name.
            (Accepts::Choice { names, .. }, Some(get)) => {
                let i = get(d).max(0.0) as usize;
                *d = params::set_number(d, row, turn(i, names.len(), up) as f64);
                if look.follows {
                    if let Ok(followed) = params::follow_material(d.clone()) {
                        *d = followed;
                    }
                }
            }
            _ => return s,
        }
        if let Some(cycled) = look.cycled {
            cycled(d);
        }
        s
    }

    /// The design (or setup) with this field set from typed text (units allowed), validated.
    pub fn parsed<S: Tunable>(self, s: &S, text: &str) -> Result<S, ThudError> {
        let t = text.trim();
        let next = match (self.kind(), self.display_unit(), self.range()) {
            // A count (of the engine's table, or the ensemble size), read as the command line
            // reads its flag.
            (None, Some(_), Some(r)) => self.set(s, r.parse_count(self.param(), t)? as f64)?,
            // A plain number is in the unit shown.
            (Some(_), Some((_, k)), _) if t.parse::<f64>().is_ok() => {
                self.set(s, t.parse::<f64>().unwrap_or(f64::NAN) * k)?
            }
            (Some(kind), _, _) => self.set(s, units::parse(self.param(), t, kind)?)?,
            (None, _, _) => self.parse_choice(s, t)?,
        };
        self.applies(&next, t)?;
        self.checked(self.then(next))
    }

    /// Refuses a number typed into a row the design still does not use after it (shown as —:
    /// the ball's ν without materials), naming the field that makes it apply.
    fn applies<S: Tunable>(self, next: &S, typed: &str) -> Result<(), ThudError> {
        let Some(row) = self.row().filter(|r| matches!(r.accepts, Accepts::Quantity { .. })) else { return Ok(()) };
        if self.get(next.design()).is_some() {
            return Ok(());
        }
        let needed = row.requires.and_then(|n| Knob::ALL.into_iter().find(|k| k.rows().contains(&n)));
        let why = needed.map_or("this design".to_string(), |k| format!("a design without {}", k.label()));
        Err(ThudError::invalid(self.param(), format!("'{typed}' does not apply to {why}")))
    }

    /// Parses a choice field: a name of the row's (or a word of the look's, or the start of a
    /// name), on/off for a switch; the look's own parse for a field of several rows.
    fn parse_choice<S: Tunable>(self, s: &S, t: &str) -> Result<S, ThudError> {
        let mut s = s.clone();
        let (d, look) = (s.design_mut(), self.look());
        let low = t.to_ascii_lowercase();
        let bad = |what: &str| ThudError::invalid(self.param(), format!("'{t}'; expected {what}"));
        let word = || look.words.iter().find(|(w, _)| *w == low).map(|&(_, i)| i);
        if let Some(parse) = look.parse {
            parse(d, t)?;
            return Ok(s);
        }
        match self.row().map(|r| (r, &r.accepts)) {
            Some((row, Accepts::Choice { names, .. })) => {
                let i = names
                    .iter()
                    .position(|n| *n == low)
                    .or_else(word)
                    .or_else(|| names.iter().position(|n| look.prefix && !low.is_empty() && n.starts_with(&low)))
                    .ok_or_else(|| bad(&one_of(names)))?;
                *d = params::set_number(d, row, i as f64);
                if look.follows {
                    *d = params::follow_material(d.clone())?;
                }
            }
            Some((row, Accepts::Switch { .. })) => {
                let on = match low.as_str() {
                    "on" | "yes" | "true" => 1,
                    "off" | "no" | "false" => 0,
                    _ => word().ok_or_else(|| bad("on or off"))?,
                };
                *d = params::set_number(d, row, on as f64);
            }
            _ => return Err(bad("a number")),
        }
        Ok(s)
    }
}

/// The fields whose name matches `typed` (the `/` filter), best first: the label or the
/// command-line name equal to it, then starting with it, then a word of the label starting
/// with it, then containing it; in panel order within each (all fields for nothing typed).
/// Case is ignored; "th" finds θ (its name is `theta`).
pub fn find(typed: &str) -> Vec<Knob> {
    let q = typed.trim().to_lowercase();
    let rank = |k: Knob| -> Option<u8> {
        if q.is_empty() {
            return Some(0);
        }
        let names = [k.label().to_lowercase(), k.param().to_lowercase()];
        if names.contains(&q) {
            Some(0)
        } else if names.iter().any(|n| n.starts_with(&q)) {
            Some(1)
        } else if names[0].split([' ', '-']).any(|w| w.starts_with(&q)) {
            Some(2)
        } else if names.iter().any(|n| n.contains(&q)) {
            Some(3)
        } else {
            None
        }
    };
    let mut hits: Vec<(u8, usize, Knob)> =
        Knob::ALL.into_iter().enumerate().filter_map(|(i, k)| rank(k).map(|r| (r, i, k))).collect();
    hits.sort_by_key(|&(r, i, _)| (r, i));
    hits.into_iter().map(|(_, _, k)| k).collect()
}

/// The index after (`up`) or before `i` of `n`, round.
fn turn(i: usize, n: usize, up: bool) -> usize {
    if up {
        (i + 1) % n
    } else {
        (i + n - 1) % n
    }
}

/// `names` as a message lists them: "single, dipole or quadrupole".
fn one_of(names: &[&str]) -> String {
    match names.split_last() {
        Some((last, [])) => (*last).to_string(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The forcing frequency a force starts at when none is set: the structure's natural
/// frequency, exactly the value the response band is centred on, or 1 Hz without one (no
/// spring, overdamped).
fn start_frequency_hz(d: &Design) -> f64 {
    let f = compute::natural_frequency_hz(d);
    if f > 0.0 {
        f
    } else {
        1.0
    }
}

/// After a change of the force: a force switched on while f is unset gets f at
/// [`start_frequency_hz`] (a force needs a frequency; the status line shows both).
fn force_frequency(d: &mut Design) {
    if d.damper.force_n > 0.0 && d.damper.freq_hz == 0.0 {
        d.damper.freq_hz = start_frequency_hz(d);
    }
}

/// Puts θ back inside the valid range of the source type after the source changed.
fn clamp_theta(d: &mut Design) {
    let (lo, hi) = d.radiation.source.theta_range_deg();
    let deg = d.observer.theta_rad.to_degrees().clamp(lo, hi);
    d.observer.theta_rad = deg.to_radians();
}

/// The materials field (rows `sphere` and `plate`) as shown: `steel/steel`, or off.
fn show_materials(d: &Design) -> String {
    match &d.materials {
        None => "off (K_HZ)".into(),
        Some(m) => format!("{}/{}", m.sphere, m.plate),
    }
}

/// The next ball material from the current one (whatever its plate and ν; off before the
/// first); the plate and a ν the user set are theirs and stay, and the ball's density follows
/// its material (the engine's one ball rule).
fn cycle_materials(d: &mut Design, up: bool) {
    let all: Vec<Option<Materials>> =
        std::iter::once(None).chain(MATERIALS.iter().map(|m| Some(Materials::new(m.name, "steel")))).collect();
    let sphere = |m: &Option<Materials>| m.as_ref().map(|m| m.sphere.clone());
    let i = all.iter().position(|m| sphere(m) == sphere(&d.materials)).unwrap_or(0);
    let mut next = all[turn(i, all.len(), up)].clone();
    if let (Some(next), Some(now)) = (next.as_mut(), d.materials.as_ref()) {
        next.plate.clone_from(&now.plate);
        next.sphere_nu = now.sphere_nu;
    }
    d.materials = next;
    if let Ok(followed) = params::follow_material(d.clone()) {
        *d = followed;
    }
}

/// The materials typed: `brass/steel`, `brass` (on steel), or off; the ball's ν stays.
fn parse_materials(d: &mut Design, t: &str) -> Result<(), ThudError> {
    let low = t.to_ascii_lowercase();
    d.materials = match low.as_str() {
        "off" | "none" | "" => None,
        _ => {
            let (s, p) = low.split_once('/').unwrap_or((low.as_str(), "steel"));
            let (s, p) = (crate::contact::material(s)?, crate::contact::material(p)?);
            Some(Materials {
                sphere_nu: d.materials.as_ref().and_then(|m| m.sphere_nu),
                ..Materials::new(s.name, p.name)
            })
        }
    };
    *d = params::follow_material(d.clone())?;
    Ok(())
}

/// The solver field (rows `solver` and `dt`) as shown: `event`, or `newmark 1µs`.
fn show_solver(d: &Design) -> String {
    match d.solver {
        Solver::Event => "event".into(),
        Solver::Newmark { dt_s } => format!("newmark {}µs", sig(dt_s * 1e6, 2)),
    }
}

/// Event ↔ Newmark at the explorer's step [`TUI_NEWMARK_DT_S`].
fn cycle_solver(d: &mut Design, _up: bool) {
    d.solver = match d.solver {
        Solver::Event => Solver::Newmark { dt_s: TUI_NEWMARK_DT_S },
        Solver::Newmark { .. } => Solver::Event,
    }
}

/// The solver typed: `event`, `newmark` (at [`TUI_NEWMARK_DT_S`]), or a Newmark step
/// (`1e-7`, `newmark 1e-7`).
fn parse_solver(d: &mut Design, t: &str) -> Result<(), ThudError> {
    d.solver = match t.to_ascii_lowercase().as_str() {
        "event" => Solver::Event,
        "newmark" => Solver::Newmark { dt_s: TUI_NEWMARK_DT_S },
        _ => Solver::Newmark { dt_s: units::parse("dt", t.trim_start_matches("newmark").trim(), Kind::Time)? },
    };
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::acoustics::Source;

    #[test]
    fn mass_steps_in_grams_and_snaps() {
        let d = Design::default();
        let up = Knob::MASS.stepped(&d, true, false).unwrap();
        assert!((up.damper.impact_mass_kg - 0.0415).abs() < 1e-12, "{}", up.damper.impact_mass_kg);
        let fine = Knob::MASS.stepped(&d, true, true).unwrap();
        assert!((fine.damper.impact_mass_kg - 0.0406).abs() < 1e-12);
        assert_eq!(Knob::MASS.display(&d), "40.50 g");
    }

    #[test]
    fn typed_values_with_units_and_refusals() {
        let d = Design::default();
        assert!((Knob::GAP.parsed(&d, "3cm").unwrap().damper.gap_m - 0.03).abs() < 1e-15);
        assert!(Knob::GAP.parsed(&d, "-3cm").is_err());
        assert!(Knob::MASS.parsed(&d, "abc").is_err());
        assert!(Knob::THETA.parsed(&d, "120").is_err(), "quadrupole θ is 0–90°");
        assert_eq!(Knob::SOURCE.parsed(&d, "dip").unwrap().radiation.source, Source::Dipole);
        let m = Knob::MATERIALS.parsed(&d, "brass/steel").unwrap();
        assert_eq!(m.materials.as_ref().unwrap().sphere, "brass");
    }

    #[test]
    fn cycling_source_keeps_theta_valid() {
        let mut d = Design::default();
        d.radiation.source = Source::Single;
        d.observer.theta_rad = 150f64.to_radians();
        let q = Knob::SOURCE.stepped(&d, false, false).unwrap();
        assert_eq!(q.radiation.source, Source::Quadrupole);
        assert!((q.observer.theta_rad.to_degrees() - 90.0).abs() < 1e-9);
    }

    #[test]
    fn the_balls_poisson_ratio_applies_with_materials_only() {
        let nu = row_field("sphere-poisson");
        let d = Design::default();
        assert_eq!(nu.display(&d), "—", "no materials: no ball ν");
        assert_eq!(nu.stepped(&d, true, false).unwrap(), d, "a step changes nothing that is not there");
        let e = nu.parsed(&d, "0.28").unwrap_err().to_string();
        assert_eq!(e, "invalid sphere-poisson: '0.28' does not apply to a design without materials");
        let steel = Knob::MATERIALS.parsed(&d, "steel/steel").unwrap();
        assert_eq!(nu.display(&steel), "0.3000", "the material's own ν");
        let given = nu.parsed(&steel, "0.28").unwrap();
        assert_eq!(given.materials.as_ref().unwrap().sphere_nu, Some(0.28));
        assert_eq!(nu.display(&given), "0.2800");
        assert!(
            given.clone().check().unwrap().damper.k_hz < steel.clone().check().unwrap().damper.k_hz,
            "softer: Eq 2"
        );
        assert!(nu.parsed(&steel, "0.7").unwrap_err().to_string().starts_with("invalid sphere-poisson: "));
    }

    /// → on the materials field goes to the ball material after the current one, whatever the
    /// plate and the ball's ν, and keeps both (they are the user's): it used to restart from the
    /// first material and drop them.
    #[test]
    fn cycling_the_materials_starts_from_the_current_ball_and_keeps_plate_and_nu() {
        let d = Design::default();
        let nu = row_field("sphere-poisson");
        let set = nu.parsed(&Knob::MATERIALS.parsed(&d, "brass/aluminium").unwrap(), "0.28").unwrap();
        let next = Knob::MATERIALS.stepped(&set, true, false).unwrap();
        let after = |name: &str| MATERIALS[MATERIALS.iter().position(|m| m.name == name).unwrap() + 1].name;
        let m = next.materials.as_ref().unwrap();
        assert_eq!((m.sphere.as_str(), m.plate.as_str(), m.sphere_nu), (after("brass"), "aluminium", Some(0.28)));
        let back = Knob::MATERIALS.stepped(&next, false, false).unwrap();
        assert_eq!(back.materials, set.materials, "← undoes →");
    }

    /// The field of the engine's row `name`, made from the row alone.
    fn row_field(name: &str) -> Knob {
        Knob::ALL.into_iter().find(|k| k.plain() && k.rows() == [name]).unwrap()
    }

    #[test]
    fn fields_made_from_table_rows_set_the_design() {
        let d = Design::default();
        let w0 = row_field("ball-velocity");
        assert_eq!(w0.parsed(&d, "0.5").unwrap().damper.ball_velocity_m_s, 0.5);
        assert!(w0.parsed(&d, "1e3").is_err(), "out of the row's range");
        let rho = row_field("density");
        assert_eq!(rho.parsed(&d, "1000").unwrap().ball, crate::design::BallSize::Density(1000.0));
        let n = row_field("periods");
        assert_eq!(n.stepped(&d, true, false).unwrap().damper.steady_periods, 2 * d.damper.steady_periods);
        assert!(n.parsed(&d, "2.5").is_err(), "a count");
        let settle = row_field("settle");
        assert!(settle.stepped(&d, true, false).unwrap().damper.settle);
        assert_eq!(settle.display(&d), "off");
        assert_eq!(w0.display(&d), "0 m/s");
    }

    /// The field list is the engine's table: every row of [`DESIGN`] is set by exactly one
    /// field, its own (listed where the row is) unless it is a later row of a look (the plate
    /// with the materials, the Newmark step with the solver); a field of one row has the row's
    /// name (or a look's shorter one), quantity, range and unit (or a unit of the same quantity
    /// whose factor is the engine's), and one made from the row alone has the row's label,
    /// name and plain unit. The one field without a row is the ensemble size N. So a row added
    /// to the table is a field with no line of the explorer's.
    #[test]
    fn every_row_of_the_table_is_one_field_with_its_name_unit_and_range() {
        for (i, p) in DESIGN.iter().enumerate() {
            let owners: Vec<Knob> = Knob::ALL.into_iter().filter(|k| k.rows().contains(&p.name)).collect();
            assert_eq!(owners.len(), 1, "{}: set by {owners:?}", p.name);
            let k = owners[0];
            assert_eq!(k.rows()[0] == p.name, k.field().row == i, "{}: listed at its own row", p.name);
            assert_eq!(k.group(), DESIGN[k.field().row].group);
            if k.rows() != [p.name] {
                continue;
            }
            assert_eq!(k.row().map(|r| r.name), Some(p.name));
            assert!(k.param() == p.name || !k.look().name.is_empty(), "{}", p.name);
            assert_eq!(k.range().as_ref(), p.range(), "{}: the row's range", p.name);
            let kind = match p.accepts {
                Accepts::Quantity { kind, .. } => Some(kind),
                _ => None,
            };
            assert_eq!(k.kind(), kind, "{}", p.name);
            match (kind, k.display_unit()) {
                (Some(_), Some((unit, to))) if unit == p.unit() => assert_eq!(to, 1.0, "{}", p.name),
                (Some(kind), Some((unit, to))) => {
                    let one = units::parse(p.name, &format!("1{unit}"), kind).ok();
                    assert_eq!(one, Some(to), "{}: 1 {unit} is {to} {}", p.name, p.unit());
                    assert!((to * k.look().to_shown - 1.0).abs() < 1e-15, "{}: {unit} both ways", p.name);
                }
                (Some(_), None) => panic!("{}: a quantity without a unit", p.name),
                (None, unit) => assert_eq!(unit.is_some(), p.range().is_some(), "{}: a count's unit", p.name),
            }
            if k.plain() {
                assert_eq!((k.label(), k.param(), k.what()), (p.label, p.name, p.help));
                assert_eq!(
                    k.display_unit().map(|(unit, _)| unit),
                    p.range().map(|r| if kind.is_some() { p.unit() } else { r.unit })
                );
            }
        }
        let own: Vec<Knob> = Knob::ALL.into_iter().filter(|k| k.rows().is_empty()).collect();
        assert_eq!(own, [Knob::RUNS], "the explorer's own fields");
        assert_eq!(Knob::RUNS.range(), Some(limits::ENSEMBLE));
        assert_eq!(Knob::ALL.last(), Some(&Knob::RUNS), "the ensemble size last, with the study");
        // Grouped as the table groups its rows, and in table order inside a group.
        let at = |k: &Knob| (Group::ALL.iter().position(|g| *g == k.group()), k.field().row);
        assert!(Knob::ALL.windows(2).all(|w| at(&w[0]) < at(&w[1])), "{:?}", Knob::ALL);
        // Every look is of a row of the table and gives a field; names are unique.
        for look in LOOKS {
            assert!(Knob::ALL.iter().any(|k| k.rows() == look.rows), "{:?}", look.rows);
        }
        for k in Knob::ALL {
            assert_eq!(Knob::named(k.param()), k, "{} names one field", k.param());
        }
    }

    #[test]
    fn the_filter_finds_theta_from_th_and_each_field_from_its_name() {
        assert_eq!(find("th").first(), Some(&Knob::THETA));
        assert_eq!(find("θ").first(), Some(&Knob::THETA));
        assert_eq!(find("TH").first(), Some(&Knob::THETA), "case is ignored");
        assert_eq!(find("gap").first(), Some(&Knob::GAP));
        assert_eq!(find("").len(), Knob::ALL.len());
        assert!(find("zzz").is_empty());
        for k in Knob::ALL {
            assert_eq!(find(k.param()).first(), Some(&k), "{} finds itself first", k.param());
        }
    }

    #[test]
    fn step_below_zero_is_refused() {
        let mut d = Design::default();
        d.damper.impact_mass_kg = 0.001;
        assert!(Knob::MASS.stepped(&d, false, false).is_err());
    }
}
