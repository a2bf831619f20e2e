// Over 800 lines: one search problem (its variables, objectives, constraints and evaluation) and the searchers over it.
//! The design search of `thud design`: the best dampers within a user's limits, as a Pareto
//! front.
//!
//! A [`Problem`] is a base design, its [`Variable`]s (a numeric row of [`params::DESIGN`] over
//! a range in the row's plain unit, or a choice among names: `sphere=steel,acrylic,nylon`), its
//! [`Objective`]s (a result column, as `thud sweep --vary` writes it, to minimise or maximise),
//! its [`Constraint`]s (`COLUMN<=VALUE` on a result or a parameter) and, for a forced design,
//! an optional band of forcing frequencies over which every result is taken at its worst.
//!
//! One design is evaluated by [`Problem::evaluate`]: the base design with each variable set by
//! `study::set` (a choice of material resolved as the explorer resolves it), checked again as a
//! whole ([`Design::check`]) and run by [`design::evaluate`]: the same code path as one cell of
//! `thud sweep --vary` ([`study::sweep_cells`]) and as `thud simulate` of the saved design, so a
//! front design run again gives exactly its printed objectives.
//!
//! The optimiser is NSGA-II from the `moors` crate (chosen by measurement: docs/model.md,
//! "Design search"), on genes in [0, 1] that [`Problem::decode`] maps to the variables. Every
//! design the optimiser asks for is evaluated once (a cache keyed by the decoded point: NSGA-II
//! re-evaluates its survivors each generation, which costs nothing here), each batch on rayon's
//! pool in a fixed order, so a search is the same for a given seed whatever the thread count.
//! The front is the non-dominated set of *every* feasible design evaluated (an archive), not
//! only of the last population. [`random_search`] and [`latin_hypercube`] evaluate the same
//! budget by the same path, the baselines the optimiser must beat.
//!
//! Measured beside the defaults and kept as [`Tuning`] options (none won over 100 seeds): two
//! phases of one budget ([`Narrowing`]: a second `moors` run over the box around the first's
//! front) and a Gaussian step that shrinks as the budget is spent ([`Tuning::sigma_end`]). No
//! optimiser is written here for them: each phase is a `moors` run; what is written by hand is
//! the box (the front's span widened), the first population handed to `moors`' sampler and the
//! step the mutation reads at each child, because `moors` has no restart over a narrowed box
//! and no step schedule of its own.
//!
//! The hypervolume of a two-objective front is computed here ([`hypervolume_2d`]): in two
//! dimensions it is one sort and a sum of rectangles, exact, a dozen lines; a crate for it
//! would bring a C library (the Fonseca et al. code) for what is needed in 2-D only. With more
//! objectives no hypervolume is reported.

use std::cell::{Cell, RefCell};
use std::collections::{BTreeMap, HashMap};
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

use ndarray::Array2;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::design::search_operators::Sampler;
pub use crate::design::search_operators::{Algorithm, Distinct, HypervolumeSurvival, Mutation, Start};
use crate::design::{self, Design, Materials, Metrics, Steady, ValidDesign};
use crate::draws::SplitMix64;
use crate::error::ThudError;
use crate::limits::{self, Range};
use crate::params::{self, Accepts, DesignDraft, Param, Spelling};
use crate::study;
use crate::units::{self, Kind};

/// A variable of the search.
#[derive(Clone)]
pub enum Variable {
    /// A numeric row over `[lo, hi]` in the row's plain unit (a count rounded).
    Range { row: &'static Param<DesignDraft>, lo: f64, hi: f64 },
    /// One of `options` (material names for `sphere`/`plate`, choice names otherwise).
    Choice { row: &'static Param<DesignDraft>, options: Vec<String> },
}

impl std::fmt::Debug for Variable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Variable::Range { row, lo, hi } => write!(f, "{}={lo}:{hi}", row.name),
            Variable::Choice { row, options } => write!(f, "{}={}", row.name, options.join(",")),
        }
    }
}

impl Variable {
    /// `NAME=FROM:TO` (a trailing `:N` is accepted and unused: the search picks the values),
    /// each end in the row's units and checked against the row's range, as `sweep --vary`
    /// checks its ends.
    pub fn parse_range(text: &str) -> Result<Variable, ThudError> {
        let Some((name, spec)) = text.split_once('=') else {
            return Err(ThudError::invalid("--vary", format!("'{text}'; expected NAME=FROM:TO, e.g. mass=20g:120g")));
        };
        let row = study::numeric_row(name, Spelling::Flag)?;
        let param = format!("--vary {}", row.name);
        let parts: Vec<&str> = spec.split(':').collect();
        let ([from, to] | [from, to, _]) = parts[..] else {
            return Err(ThudError::invalid(&param, format!("'{spec}'; expected FROM:TO, e.g. 20g:120g")));
        };
        // N is unused (the search picks the values), but when given it is a count as a sweep's.
        if let [_, _, n] = parts[..] {
            limits::GRID_N.parse_count(&param, n)?;
        }
        let value = |t: &str| -> Result<f64, ThudError> {
            match row.accepts {
                Accepts::Quantity { kind, range, .. } => range.check_as(&param, units::parse(&param, t, kind)?),
                Accepts::Count { range, .. } => Ok(range.parse_count(&param, t)? as f64),
                _ => Err(ThudError::invalid(&param, "not a number to vary")),
            }
        };
        let (lo, hi) = (value(from)?, value(to)?);
        if lo >= hi {
            return Err(ThudError::invalid(&param, format!("'{spec}': FROM must be below TO")));
        }
        Ok(Variable::Range { row, lo, hi })
    }

    /// `NAME=A,B,C`: a material row (`sphere`, `plate`) or a choice row that sets the design
    /// (`source`, `model`, …), with at least two distinct known names.
    pub fn parse_choice(text: &str) -> Result<Variable, ThudError> {
        let Some((name, list)) = text.split_once('=') else {
            return Err(ThudError::invalid(
                "--choose",
                format!("'{text}'; expected NAME=A,B,…, e.g. sphere=steel,acrylic,nylon"),
            ));
        };
        let canonical = name.trim().replace('_', "-");
        let row = params::DESIGN.iter().find(|p| p.name == canonical && is_choosable(p)).ok_or_else(|| {
            ThudError::invalid("--choose", format!("'{name}' is not a choice; one of: {}", choosable()))
        })?;
        let param = format!("--choose {}", row.name);
        let options: Vec<String> = list.split(',').map(|s| s.trim().to_string()).collect();
        for (i, o) in options.iter().enumerate() {
            if o.is_empty() {
                return Err(ThudError::invalid(&param, format!("'{list}': an empty name")));
            }
            if options[..i].contains(o) {
                return Err(ThudError::invalid(&param, format!("'{o}' is given twice")));
            }
            match row.accepts {
                Accepts::Choice { names, .. } if !names.contains(&o.as_str()) => {
                    return Err(ThudError::invalid(&param, format!("'{o}' is not one of: {}", names.join(", "))));
                }
                Accepts::Name { .. } => {
                    crate::contact::material(o).map_err(|e| ThudError::invalid(&param, e.to_string()))?;
                }
                _ => {}
            }
        }
        if options.len() < 2 {
            return Err(ThudError::invalid(&param, format!("'{list}': give at least two names, e.g. A,B")));
        }
        Ok(Variable::Choice { row, options })
    }

    /// The row's name as in the table (`mass`).
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Variable::Range { row, .. } | Variable::Choice { row, .. } => row.name,
        }
    }

    /// The variable's key in results: the column of `sweep --vary` (`mass_kg`), a choice bare.
    #[must_use]
    pub fn column(&self) -> String {
        match self {
            Variable::Range { row, .. } => study::column(row.name, row.unit()),
            Variable::Choice { row, .. } => row.name.replace('-', "_"),
        }
    }

    /// The value of gene `g` (clamped to [0, 1]).
    fn decode(&self, g: f64) -> Value {
        let g = if g.is_finite() { g.clamp(0.0, 1.0) } else { 0.0 };
        match self {
            Variable::Range { row, lo, hi } => {
                let v = lo + g * (hi - lo);
                let v = if matches!(row.accepts, Accepts::Count { .. }) { v.round() } else { v.min(*hi) };
                Value::Number(v)
            }
            Variable::Choice { options, .. } => {
                let i = ((g * options.len() as f64) as usize).min(options.len() - 1);
                Value::Choice(options[i].clone())
            }
        }
    }

    /// `d` with this variable set to `value`, unchecked.
    fn set(&self, d: Design, value: &Value) -> Result<Design, ThudError> {
        match (self, value) {
            (Variable::Range { row, .. }, Value::Number(v)) => Ok(study::set(d, row, *v)),
            (Variable::Choice { row, .. }, Value::Choice(name)) => match row.accepts {
                Accepts::Name { .. } => {
                    let mut d = d;
                    let mut m = d.materials.clone().unwrap_or_else(|| Materials::new("steel", "steel"));
                    if row.name == "plate" {
                        m.plate.clone_from(name);
                    } else {
                        m.sphere.clone_from(name);
                        m.sphere_nu = None;
                    }
                    d.materials = Some(m);
                    params::follow_material(d)
                }
                Accepts::Choice { names, .. } => {
                    let i = names.iter().position(|n| n == name).unwrap_or(0);
                    Ok(params::set_number(&d, row, i as f64))
                }
                _ => Ok(d),
            },
            _ => Ok(d),
        }
    }
}

/// Rows `--choose` takes: the materials and the choices that set the design alone.
fn is_choosable(p: &Param<DesignDraft>) -> bool {
    match p.accepts {
        Accepts::Name { .. } => matches!(p.name, "sphere" | "plate"),
        Accepts::Choice { .. } => p.get.is_some(),
        _ => false,
    }
}

/// The rows `--choose` takes, for a message.
fn choosable() -> String {
    params::DESIGN.iter().filter(|p| is_choosable(p)).map(|p| p.name).collect::<Vec<_>>().join(", ")
}

/// The value of one variable at one design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Value {
    /// In the row's plain unit.
    Number(f64),
    /// A name.
    Choice(String),
}

impl Value {
    fn key(&self) -> u64 {
        match self {
            Value::Number(v) => v.to_bits(),
            Value::Choice(s) => {
                s.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3))
            }
        }
    }
}

/// A result column an objective or a constraint reads: the metrics `thud sweep --vary` writes
/// (same names), and with a force the steady state's amplitude, reduction and Leq.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Column {
    NImpacts,
    Inclination,
    InclinationFit,
    U0Max,
    ZdotAbsMax,
    SplMax,
    ContactDuration,
    RestitutionMean,
    SteadyAmplitude,
    SteadyReduction,
    SteadyLeq,
}

/// Every column, with its name.
pub const COLUMNS: [(Column, &str); 11] = [
    (Column::NImpacts, "n_impacts"),
    (Column::Inclination, "inclination_cm_s"),
    (Column::InclinationFit, "inclination_fit_cm_s"),
    (Column::U0Max, "u0_max_m_s"),
    (Column::ZdotAbsMax, "zdot_abs_max_m_s"),
    (Column::SplMax, "spl_max_db"),
    (Column::ContactDuration, "contact_duration_s"),
    (Column::RestitutionMean, "restitution_mean"),
    (Column::SteadyAmplitude, "steady_amplitude_m"),
    (Column::SteadyReduction, "steady_reduction_db"),
    (Column::SteadyLeq, "steady_leq_db"),
];

impl Column {
    /// The column called `name`, or None.
    #[must_use]
    pub fn named(name: &str) -> Option<Column> {
        COLUMNS.iter().find(|(_, n)| *n == name.trim()).map(|(c, _)| *c)
    }

    /// Its name as the CSV and JSON write it.
    #[must_use]
    pub fn name(self) -> &'static str {
        COLUMNS.iter().find(|(c, _)| *c == self).map_or("", |(_, n)| n)
    }

    /// The column's value in one run (None where the run has none: no impact, no force).
    #[must_use]
    pub fn value(self, m: &Metrics, steady: Option<&Steady>) -> Option<f64> {
        match self {
            Column::NImpacts => Some(m.n_impacts as f64),
            Column::Inclination => m.inclination_cm_s,
            Column::InclinationFit => m.inclination_fit_cm_s,
            Column::U0Max => Some(m.u0_max_m_s),
            Column::ZdotAbsMax => Some(m.zdot_abs_max_m_s),
            Column::SplMax => m.spl_max_db,
            Column::ContactDuration => m.contact_duration_s,
            Column::RestitutionMean => m.restitution_mean,
            Column::SteadyAmplitude => steady.map(|s| s.amplitude_m),
            Column::SteadyReduction => steady.and_then(|s| s.reduction_db),
            Column::SteadyLeq => steady.and_then(|s| s.leq_db),
        }
    }

    fn forced(self) -> bool {
        matches!(self, Column::SteadyAmplitude | Column::SteadyReduction | Column::SteadyLeq)
    }
}

/// The names of every column, for a message.
fn column_names() -> String {
    COLUMNS.iter().map(|(_, n)| *n).collect::<Vec<_>>().join(", ")
}

/// Which way an objective goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sense {
    Minimize,
    Maximize,
}

/// One objective: a column to minimise or maximise (over a band: its worst value there).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Objective {
    pub column: Column,
    pub sense: Sense,
}

impl Objective {
    /// `--minimize COLUMN` / `--maximize COLUMN`.
    pub fn parse(text: &str, sense: Sense) -> Result<Objective, ThudError> {
        let flag = match sense {
            Sense::Minimize => "--minimize",
            Sense::Maximize => "--maximize",
        };
        let column = Column::named(text).ok_or_else(|| {
            ThudError::invalid(flag, format!("'{text}' is not a result column; one of: {}", column_names()))
        })?;
        Ok(Objective { column, sense })
    }

    /// Of two values of this objective, the worse one.
    fn worse(self, a: f64, b: f64) -> f64 {
        match self.sense {
            Sense::Minimize => a.max(b),
            Sense::Maximize => a.min(b),
        }
    }
}

/// What a constraint bounds.
#[derive(Clone)]
pub enum Bound {
    /// A result column (over a band: its worst value there).
    Result(Column),
    /// A numeric parameter of the design (the row's plain unit).
    Param(&'static Param<DesignDraft>),
}

/// `COLUMN<=VALUE` or `COLUMN>=VALUE`.
#[derive(Clone)]
pub struct Constraint {
    pub bound: Bound,
    /// True for `<=`, false for `>=`.
    pub at_most: bool,
    /// In the column's or the row's plain unit.
    pub value: f64,
    /// As the user typed it.
    pub text: String,
}

impl std::fmt::Debug for Constraint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl Constraint {
    /// `COLUMN<=VALUE` / `COLUMN>=VALUE` (`<`, `>` read the same): a result column (a plain
    /// number in its unit) or a numeric parameter (its units accepted: `mass<=60g`).
    pub fn parse(text: &str) -> Result<Constraint, ThudError> {
        let flag = "--require";
        let (name, at_most, value) = if let Some((n, v)) = text.split_once("<=").or_else(|| text.split_once('<')) {
            (n, true, v)
        } else if let Some((n, v)) = text.split_once(">=").or_else(|| text.split_once('>')) {
            (n, false, v)
        } else {
            return Err(ThudError::invalid(
                flag,
                format!("'{text}'; expected COLUMN<=VALUE or COLUMN>=VALUE, e.g. spl_max_db<=100"),
            ));
        };
        let name = name.trim();
        let value = value.trim();
        let (bound, value) = if let Some(c) = Column::named(name) {
            let v: f64 = value
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| ThudError::invalid(flag, format!("'{text}': '{value}' is not a number")))?;
            (Bound::Result(c), v)
        } else {
            let row = study::numeric_row(name, Spelling::Flag).map_err(|_| {
                ThudError::invalid(
                    flag,
                    format!(
                        "'{text}': '{name}' is neither a result column ({}) nor a numeric parameter",
                        column_names()
                    ),
                )
            })?;
            let kind = match row.accepts {
                Accepts::Quantity { kind, .. } => kind,
                _ => Kind::Number,
            };
            let v = units::parse(flag, value, kind).map_err(|e| ThudError::invalid(flag, format!("'{text}': {e}")))?;
            if !v.is_finite() {
                return Err(ThudError::invalid(flag, format!("'{text}': '{value}' is not a finite number")));
            }
            (Bound::Param(row), v)
        };
        Ok(Constraint { bound, at_most, value, text: text.trim().to_string() })
    }

    /// How far inside the bound `actual` is (≥ 0: met), in the bound's unit.
    fn margin(&self, actual: f64) -> f64 {
        if self.at_most {
            self.value - actual
        } else {
            actual - self.value
        }
    }
}

/// The most evaluations of one search (`--evaluations`): a count of the limits table.
pub const EVALUATIONS: &Range = &limits::EVALUATIONS;

/// A design search.
#[derive(Debug, Clone)]
pub struct Problem {
    pub base: ValidDesign,
    pub variables: Vec<Variable>,
    pub objectives: Vec<Objective>,
    pub constraints: Vec<Constraint>,
    /// Forcing frequencies (Hz) over which each result is taken at its worst; empty: the
    /// design's own.
    pub band_hz: Vec<f64>,
    /// Robust mode: each result taken over an ensemble of ball starts ([`Robust`]); None: the
    /// centred ball's one run.
    pub robust: Option<Robust>,
}

/// Robust mode (`--ensemble N --quantile Q`): each design runs from the N ball starts of the
/// engine's ensemble ([`crate::ensemble::ball_positions`]) and each result is the value a
/// fraction Q of the starts do at least as well as: the Q-quantile of a column minimised (or
/// bounded above, `COLUMN<=V`), the (1 − Q)-quantile of one maximised (or bounded below), by
/// nearest rank as the ensemble's percentiles are taken (so every value is that of one
/// actual run; a run without the column ranks below every run with it).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Robust {
    /// Ball starts N (at least 1; 1 is the centred ball alone).
    pub runs: usize,
    /// Q in (0, 1].
    pub quantile: f64,
}

impl Robust {
    /// Checks N against the ensemble's range and Q in (0, 1], naming the flags.
    pub fn new(runs: usize, quantile: f64) -> Result<Robust, ThudError> {
        if runs == 0 {
            return Err(ThudError::invalid("--ensemble", "0 runs; an ensemble needs at least 1"));
        }
        if !(quantile > 0.0 && quantile <= 1.0) {
            return Err(ThudError::invalid(
                "--quantile",
                format!("'{quantile}' is not a fraction above 0 and at most 1 (e.g. 0.9)"),
            ));
        }
        Ok(Robust { runs, quantile })
    }

    /// The 1-based rank in ascending order of the value whose worse side is high (`high`) or
    /// low, among `n` values: ⌈q·n⌉ with q = Q or 1 − Q, at least 1 (a float's last bit
    /// forgiven: 0.7 × 10 is rank 7).
    fn rank(self, n: usize, high: bool) -> usize {
        let q = if high { self.quantile } else { 1.0 - self.quantile };
        (((q * n as f64) - 1e-9).ceil().max(1.0) as usize).min(n.max(1))
    }
}

/// The value of rank `robust.rank(…)` of `values` (a missing value ranked below every number):
/// the one value without robust mode.
fn quantile(values: &[Option<f64>], robust: Option<Robust>, high: bool) -> Option<f64> {
    let Some(r) = robust else { return values.first().copied().flatten() };
    let mut v = values.to_vec();
    v.sort_by(|a, b| match (a, b) {
        (Some(x), Some(y)) => x.total_cmp(y),
        _ => a.is_some().cmp(&b.is_some()),
    });
    v.get(r.rank(v.len(), high) - 1).copied().flatten()
}

/// One evaluated design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Candidate {
    /// Its place in the order of evaluation (from 0).
    pub index: usize,
    /// One value per variable.
    pub values: Vec<Value>,
    /// One value per objective, as the column reads (not negated); None where undefined.
    pub objectives: Vec<Option<f64>>,
    /// One margin per constraint (≥ 0: met); None where its column is undefined.
    pub margins: Vec<Option<f64>>,
    /// Why the design could not be run (a check it fails), if so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

impl Candidate {
    /// Whether it ran, every objective is defined and every constraint is met.
    #[must_use]
    pub fn feasible(&self) -> bool {
        self.error.is_none()
            && self.objectives.iter().all(Option::is_some)
            && self.margins.iter().all(|m| m.is_some_and(|m| m >= 0.0))
    }

    /// The objectives to minimise (a maximised one negated); None unless all are defined.
    fn minimized(&self, objectives: &[Objective]) -> Option<Vec<f64>> {
        self.objectives
            .iter()
            .zip(objectives)
            .map(|(v, o)| v.map(|v| if o.sense == Sense::Maximize { -v } else { v }))
            .collect()
    }
}

impl Problem {
    /// Checks the problem as a whole: at least one variable and objective, no row twice, a
    /// forced column or a band only with a force.
    pub fn check(&self) -> Result<(), ThudError> {
        if self.variables.is_empty() {
            return Err(ThudError::invalid("--vary", "no variable; give --vary NAME=FROM:TO or --choose NAME=A,B"));
        }
        if self.objectives.is_empty() {
            return Err(ThudError::invalid("--minimize", "no objective; give --minimize COLUMN or --maximize COLUMN"));
        }
        for (i, v) in self.variables.iter().enumerate() {
            if self.variables[..i].iter().any(|w| w.name() == v.name()) {
                return Err(ThudError::invalid(
                    format!("--vary {}", v.name()),
                    "varied twice; give each parameter once",
                ));
            }
        }
        for (i, o) in self.objectives.iter().enumerate() {
            if self.objectives[..i].iter().any(|p| p.column == o.column) {
                return Err(ThudError::invalid("--minimize", format!("{} is an objective twice", o.column.name())));
            }
        }
        let forced = self.base.damper.force_n > 0.0;
        let needs_force =
            self.objectives.iter().map(|o| o.column).chain(self.constraints.iter().filter_map(|c| match c.bound {
                Bound::Result(col) => Some(col),
                Bound::Param(_) => None,
            }));
        if !forced {
            if let Some(c) = needs_force.into_iter().find(|c| c.forced()) {
                return Err(ThudError::invalid(
                    "--force-amplitude",
                    format!("{} is a result of a forced design; give --force-amplitude and --freq", c.name()),
                ));
            }
            if !self.band_hz.is_empty() {
                return Err(ThudError::invalid(
                    "--over",
                    "a band of frequencies needs a forced design; give --force-amplitude",
                ));
            }
        }
        if self.robust.is_some() {
            let forced =
                self.objectives.iter().map(|o| o.column).chain(self.constraints.iter().filter_map(|c| match c.bound {
                    Bound::Result(col) => Some(col),
                    Bound::Param(_) => None,
                }));
            if let Some(c) = forced.into_iter().find(|c| c.forced()) {
                return Err(ThudError::invalid(
                    "--ensemble",
                    format!(
                        "{} is not taken over ball starts (an ensemble keeps no steady state); leave out --ensemble",
                        c.name()
                    ),
                ));
            }
            if self.variables.iter().any(|v| v.name() == "ball-position") {
                return Err(ThudError::invalid(
                    "--vary ball-position",
                    "the ensemble sets the ball's start; leave out --vary ball-position or --ensemble",
                ));
            }
        }
        if !self.band_hz.is_empty() && self.variables.iter().any(|v| v.name() == "freq") {
            return Err(ThudError::invalid("--vary freq", "the band --over sets the frequency; leave out --vary freq"));
        }
        Ok(())
    }

    /// The value of each variable at genes `g` (one gene per variable, in [0, 1]).
    #[must_use]
    pub fn decode(&self, g: &[f64]) -> Vec<Value> {
        self.variables.iter().zip(g).map(|(v, &g)| v.decode(g)).collect()
    }

    /// The design at `values`, checked as a whole: the one every command runs for it.
    pub fn design_at(&self, values: &[Value]) -> Result<ValidDesign, ThudError> {
        let mut d = self.base.design().clone();
        for (v, x) in self.variables.iter().zip(values) {
            d = v.set(d, x)?;
        }
        d.check()
    }

    /// The designs one point runs: the design itself, or one per frequency of the band.
    pub fn runs_at(&self, values: &[Value]) -> Result<Vec<ValidDesign>, ThudError> {
        let d = self.design_at(values)?;
        if self.band_hz.is_empty() {
            return Ok(vec![d]);
        }
        let freq = params::design_param("freq").ok_or_else(|| ThudError::invalid("--over", "no frequency row"))?;
        self.band_hz.iter().map(|&f| study::set(d.design().clone(), freq, f).check()).collect()
    }

    /// Evaluates one point (index `index` of the search): each of its runs by
    /// [`design::evaluate`], objectives and result constraints at their worst over the runs.
    #[must_use]
    pub fn evaluate(&self, index: usize, values: Vec<Value>, cancel: Option<&AtomicBool>) -> Candidate {
        let fail = |values: Vec<Value>, e: ThudError| Candidate {
            index,
            values,
            objectives: vec![None; self.objectives.len()],
            margins: vec![None; self.constraints.len()],
            error: Some(e.to_string()),
        };
        let runs = match self.runs_at(&values) {
            Ok(r) => r,
            Err(e) => return fail(values, e),
        };
        // Each run's results: one (metrics, steady) of the centred ball, or one per ball start.
        let mut evals: Vec<Vec<(Metrics, Option<Steady>)>> = Vec::with_capacity(runs.len());
        for r in &runs {
            let one = match self.robust {
                None => design::evaluate(r, 0, cancel).map(|e| vec![(e.metrics, e.steady)]),
                Some(rb) => crate::ensemble::evaluate(r, rb.runs, cancel).and_then(|e| {
                    let e = e.ok_or_else(|| ThudError::invalid("--ensemble", "stopped"))?;
                    Ok(e.ensemble.iter().map(|m| (m.metrics, None)).collect())
                }),
            };
            match one {
                Ok(e) => evals.push(e),
                Err(e) => return fail(values, e),
            }
        }
        // A column over the runs: its quantile over the ball starts (the side `high` is worse),
        // then its worst over the band.
        let worst = |col: Column, high: bool| -> Option<f64> {
            let mut acc: Option<f64> = None;
            for e in &evals {
                let vs: Vec<Option<f64>> = e.iter().map(|(m, s)| col.value(m, s.as_ref())).collect();
                let v = quantile(&vs, self.robust, high)?;
                acc = Some(acc.map_or(v, |a: f64| if high { a.max(v) } else { a.min(v) }));
            }
            acc
        };
        let objectives = self.objectives.iter().map(|o| worst(o.column, o.sense == Sense::Minimize)).collect();
        let margins = self
            .constraints
            .iter()
            .map(|c| match c.bound {
                Bound::Result(col) => worst(col, c.at_most).map(|v| c.margin(v)),
                Bound::Param(row) => row.get.map(|get| c.margin(get(runs[0].design()))),
            })
            .collect();
        Candidate { index, values, objectives, margins, error: None }
    }

    /// The indices (into `all`) of the feasible candidates no other feasible one dominates, in
    /// the order of the first objective (then the evaluation order); equal points kept once.
    #[must_use]
    pub fn front(&self, all: &[Candidate]) -> Vec<usize> {
        let pts: Vec<(usize, Vec<f64>)> = all
            .iter()
            .enumerate()
            .filter(|(_, c)| c.feasible())
            .filter_map(|(i, c)| Some((i, c.minimized(&self.objectives)?)))
            .collect();
        let mut front: Vec<(usize, &Vec<f64>)> = Vec::new();
        for (i, p) in &pts {
            let dominated = pts.iter().any(|(j, q)| dominates(q, p) || (q == p && j < i));
            if !dominated {
                front.push((*i, p));
            }
        }
        front.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]).then(a.0.cmp(&b.0)));
        front.into_iter().map(|(i, _)| i).collect()
    }

    /// The hypervolume of `front` (indices into `all`) against `reference` (one value per
    /// objective, as the columns read): two objectives only.
    #[must_use]
    pub fn hypervolume(&self, all: &[Candidate], front: &[usize], reference: &[f64]) -> Option<f64> {
        if self.objectives.len() != 2 || reference.len() != 2 {
            return None;
        }
        let sign = |o: &Objective| if o.sense == Sense::Maximize { -1.0 } else { 1.0 };
        let r = [reference[0] * sign(&self.objectives[0]), reference[1] * sign(&self.objectives[1])];
        let pts: Vec<[f64; 2]> =
            front.iter().filter_map(|&i| all[i].minimized(&self.objectives)).map(|p| [p[0], p[1]]).collect();
        Some(hypervolume_2d(&pts, r))
    }

    /// The constraint that binds when no design is feasible: the one met by the fewest of the
    /// designs that ran, with the best margin any of them reached (negative).
    #[must_use]
    pub fn binding(&self, all: &[Candidate]) -> Option<(usize, f64)> {
        let ran: Vec<&Candidate> = all.iter().filter(|c| c.error.is_none()).collect();
        (0..self.constraints.len())
            .map(|k| {
                let met = ran.iter().filter(|c| c.margins[k].is_some_and(|m| m >= 0.0)).count();
                let best = ran.iter().filter_map(|c| c.margins[k]).fold(f64::NEG_INFINITY, f64::max);
                (k, met, best)
            })
            .min_by(|a, b| a.1.cmp(&b.1).then(a.2.total_cmp(&b.2)))
            .map(|(k, _, best)| (k, best))
    }
}

/// Refuses a search of `evaluations` designs whose work is over a cap: each corner of the
/// variables' box (every variable at its ends or choices, up to 256 corners) run as one design
/// ([`limits::check_run`]), and the sum over the budget of the longest corner's work times the
/// runs a point takes (one, or one per frequency of the band, times the ball starts of robust
/// mode) ([`limits::check_work_sum`]).
pub fn check_work(problem: &Problem, evaluations: usize, given: &dyn Fn(&str) -> bool) -> Result<(), limits::Refusal> {
    let ends: Vec<Vec<f64>> = problem
        .variables
        .iter()
        .map(|v| match v {
            Variable::Range { .. } => vec![0.0, 1.0],
            Variable::Choice { options, .. } => {
                (0..options.len()).map(|i| (i as f64 + 0.5) / options.len() as f64).collect()
            }
        })
        .collect();
    let corners: usize = ends.iter().map(Vec::len).product();
    let mut worst: Option<ValidDesign> = None;
    for i in 0..corners.min(256) {
        let mut rest = i;
        let genes: Vec<f64> = ends
            .iter()
            .map(|e| {
                let g = e[rest % e.len()];
                rest /= e.len();
                g
            })
            .collect();
        let Ok(runs) = problem.runs_at(&problem.decode(&genes)) else { continue };
        for d in runs {
            limits::check_run(&d, given, 0)?;
            if worst.as_ref().is_none_or(|w| {
                limits::sweep_work(&d, 1)[1].value > limits::sweep_work(w, 1)[1].value
                    || d.damper.duration_s > w.damper.duration_s
            }) {
                worst = Some(d);
            }
        }
    }
    let Some(w) = worst else { return Ok(()) };
    let n = evaluations * problem.band_hz.len().max(1) * problem.robust.map_or(1, |r| r.runs);
    let total = limits::sweep_work(&w, n).map(|e| e.value);
    limits::check_work_sum(&w, given, n, total)
}

/// The largest size of a value of the hypervolume's reference point: the hypervolume is a
/// product of two spans from it, so with the objectives' own values far below this it stays a
/// finite number.
pub const REFERENCE_MAX: f64 = 1e150;

/// Whether `a` dominates `b` (every objective minimised): no worse anywhere, better somewhere.
#[must_use]
pub fn dominates(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(x, y)| x <= y) && a.iter().zip(b).any(|(x, y)| x < y)
}

/// The area dominated by `points` (both objectives minimised) and bounded by `reference`:
/// points not better than the reference in both count nothing.
#[must_use]
pub fn hypervolume_2d(points: &[[f64; 2]], reference: [f64; 2]) -> f64 {
    let mut p: Vec<[f64; 2]> = points.iter().copied().filter(|p| p[0] < reference[0] && p[1] < reference[1]).collect();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let mut area = 0.0;
    let mut y = reference[1];
    for q in p {
        if q[1] < y {
            area += (reference[0] - q[0]) * (y - q[1]);
            y = q[1];
        }
    }
    area
}

/// How a search goes, after each batch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    pub evaluations: usize,
    pub front: usize,
    pub hypervolume: Option<f64>,
}

/// The settings of a search.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Settings {
    /// The budget: designs evaluated at most.
    pub evaluations: usize,
    pub seed: u64,
}

/// What a search found.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Every design evaluated, in order.
    pub all: Vec<Candidate>,
    /// The indices into `all` of the front ([`Problem::front`]).
    pub front: Vec<usize>,
    /// Whether it was cancelled before its budget was spent.
    pub partial: bool,
    /// The reference point of the hypervolume (one value per objective, as the columns read):
    /// the one given, else the worst value of each objective among the feasible designs of
    /// the first batch (two objectives only).
    pub reference: Option<Vec<f64>>,
    /// The front's hypervolume against `reference`.
    pub hypervolume: Option<f64>,
}

/// What a search has found so far, after each batch: for a progress line, or for writing the
/// front when the search is stopped.
pub type OnBatch<'a> = dyn Fn(Progress, &[Candidate], &[usize]) + Sync + 'a;

/// The archive a search fills: every point evaluated, once.
struct Archive<'a> {
    problem: &'a Problem,
    budget: usize,
    cancel: Option<&'a AtomicBool>,
    reference: Mutex<Option<Vec<f64>>>,
    on_progress: &'a OnBatch<'a>,
    state: Mutex<State>,
}

/// Each point's key and its index in the archive; the archive in order of evaluation.
type State = (HashMap<Vec<u64>, usize>, Vec<Candidate>);

impl<'a> Archive<'a> {
    fn new(
        problem: &'a Problem,
        budget: usize,
        cancel: Option<&'a AtomicBool>,
        reference: Option<&[f64]>,
        on_progress: &'a OnBatch<'a>,
    ) -> Self {
        let reference = Mutex::new(reference.map(<[f64]>::to_vec));
        Archive { problem, budget, cancel, reference, on_progress, state: Mutex::new((HashMap::new(), Vec::new())) }
    }

    /// The reference point: the one given, else fixed from the feasible designs of the first
    /// batch (the worst value of each objective), two objectives only.
    fn reference(&self, all: &[Candidate]) -> Option<Vec<f64>> {
        let mut r = self.reference.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if r.is_none() && self.problem.objectives.len() == 2 {
            let worst: Option<Vec<f64>> = self
                .problem
                .objectives
                .iter()
                .enumerate()
                .map(|(k, o)| {
                    all.iter().filter(|c| c.feasible()).filter_map(|c| c.objectives[k]).reduce(|a, b| o.worse(a, b))
                })
                .collect();
            *r = worst;
        }
        r.clone()
    }

    fn cancelled(&self) -> bool {
        self.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
    }

    /// The candidate of each row of genes (its index into the archive), evaluating the points
    /// not seen yet (in row order, on rayon's pool) while the budget lasts: None past it.
    /// `cap` bounds the evaluations of a phase (at most the budget).
    fn batch(&self, genes: &[Vec<f64>], cap: usize) -> Vec<Option<usize>> {
        let mut st = self.state.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let points: Vec<Vec<Value>> = genes.iter().map(|g| self.problem.decode(g)).collect();
        let keys: Vec<Vec<u64>> = points.iter().map(|p| p.iter().map(Value::key).collect()).collect();
        let mut new: Vec<(Vec<u64>, Vec<Value>)> = Vec::new();
        for (k, p) in keys.iter().zip(&points) {
            if !st.0.contains_key(k) && !new.iter().any(|(n, _)| n == k) {
                new.push((k.clone(), p.clone()));
            }
        }
        let room = if self.cancelled() { 0 } else { cap.min(self.budget).saturating_sub(st.1.len()) };
        new.truncate(room);
        let first = st.1.len();
        let done: Vec<Candidate> =
            new.par_iter().enumerate().map(|(i, (_, p))| self.problem.evaluate(first + i, p.clone(), None)).collect();
        if !done.is_empty() {
            for ((k, _), c) in new.into_iter().zip(done) {
                st.0.insert(k, c.index);
                st.1.push(c);
            }
            let front = self.problem.front(&st.1);
            let hypervolume = self.reference(&st.1).and_then(|r| self.problem.hypervolume(&st.1, &front, &r));
            (self.on_progress)(Progress { evaluations: st.1.len(), front: front.len(), hypervolume }, &st.1, &front);
        }
        keys.iter().map(|k| st.0.get(k).copied()).collect()
    }

    fn into_outcome(self, partial: bool) -> Outcome {
        let (_, all) = self.state.into_inner().unwrap_or_else(std::sync::PoisonError::into_inner);
        let front = self.problem.front(&all);
        let reference = self.reference.into_inner().unwrap_or_else(std::sync::PoisonError::into_inner);
        let hypervolume = reference.as_ref().and_then(|r| self.problem.hypervolume(&all, &front, r));
        Outcome { all, front, partial, reference, hypervolume }
    }
}

/// The penalty objective of a point that has no value (not run, undefined, past the budget).
pub(super) const PENALTY: f64 = 1e12;

/// The population of NSGA-II for a budget of `n` evaluations: a tenth of it, even, 8 to 100.
#[must_use]
pub fn population_size(n: usize) -> usize {
    ((n / 10).clamp(8, 100) / 2) * 2
}

/// NSGA-II (`moors`) over `problem` with `settings`: every design it asks for evaluated once
/// (at most `settings.evaluations`), the front of all of them. `cancel` stops it after the
/// batch under way (the outcome then marked partial); `on_progress` hears of each batch, with
/// the hypervolume against `reference` when given (two objectives).
pub fn search(
    problem: &Problem,
    settings: Settings,
    reference: Option<&[f64]>,
    cancel: Option<&AtomicBool>,
    on_progress: &OnBatch<'_>,
) -> Result<Outcome, ThudError> {
    search_tuned(problem, settings, Tuning::default(), reference, cancel, on_progress)
}

/// The knobs of NSGA-II; [`search`] takes the defaults (measured: docs/model.md, "Design
/// search").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tuning {
    /// The population: None for [`population_size`] of the budget.
    pub population: Option<usize>,
    /// The standard deviation of a gene's Gaussian mutation (genes span [0, 1]).
    pub sigma: f64,
    /// The chance each gene of a mutated child mutates, times the number of variables.
    pub genes_mutated: f64,
    /// The chance a child is mutated.
    pub mutation_rate: f64,
    /// The distribution index of the simulated binary crossover.
    pub crossover_eta: f64,
    /// How the first population is drawn.
    pub start: Start,
    /// The distribution index of a polynomial mutation in place of the Gaussian one (`sigma`
    /// then unused); None: Gaussian.
    pub polynomial_eta: Option<f64>,
    /// Whether a generation's children repeating a parent or each other are drawn again.
    pub distinct: bool,
    /// The algorithm of `moors` (its selection and survival; the operators above either way).
    pub algorithm: Algorithm,
    /// Children a generation: None for as many as the population.
    pub offspring: Option<usize>,
    /// Two phases of the budget, the second over the box around the first's front; None: one.
    pub narrow: Option<Narrowing>,
    /// The Gaussian mutation's standard deviation once the budget is spent, lowered from
    /// `sigma` geometrically with the designs evaluated; None: `sigma` throughout.
    pub sigma_end: Option<f64>,
}

/// The second phase of a search in two ([`Tuning::narrow`]): after a share of the budget over
/// the whole box, the rest over the box the front found so far spans.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Narrowing {
    /// The share of the budget the first phase spends over the whole box.
    pub share: f64,
    /// How far the box is widened beyond the front's span on each side, as a share of each
    /// variable's whole range.
    pub margin: f64,
    /// How far the box is widened beyond the front's span on each side besides, as a share of
    /// that span (a front long in one variable keeps it long; a ridge narrow in another is
    /// searched near it).
    pub widen: f64,
    /// The algorithm of the second phase.
    pub then: Algorithm,
    /// Whether the second phase's first population is the front's designs (else drawn).
    pub start_at_front: bool,
}

impl Default for Tuning {
    fn default() -> Self {
        Tuning {
            population: None,
            sigma: 0.1,
            genes_mutated: 1.0,
            mutation_rate: 0.5,
            crossover_eta: 15.0,
            start: Start::Uniform,
            polynomial_eta: None,
            distinct: false,
            algorithm: Algorithm::Nsga2,
            offspring: None,
            narrow: None,
            sigma_end: None,
        }
    }
}

impl Tuning {
    /// The population for a budget of `n` evaluations (at most `n`).
    #[must_use]
    pub fn population_for(&self, n: usize) -> usize {
        self.population.map_or_else(|| population_size(n), |p| (p.max(2) / 2) * 2).min(n)
    }

    /// Children a generation for a population of `pop` (at least 2, even).
    #[must_use]
    pub fn offspring_for(&self, pop: usize) -> usize {
        self.offspring.map_or(pop, |k| (k.max(2) / 2) * 2)
    }

    /// The mutation of a child over `nv` variables; with `sigma_end`, its step read from
    /// `sigma`.
    #[must_use]
    pub fn mutation(&self, nv: usize, sigma: &Rc<Cell<f64>>) -> Mutation {
        let gene_rate = (self.genes_mutated / nv.max(1) as f64).min(1.0);
        match (self.polynomial_eta, self.sigma_end) {
            (Some(eta), _) => Mutation::Polynomial { gene_rate, eta },
            (None, Some(_)) => Mutation::Shrinking { gene_rate, sigma: Rc::clone(sigma) },
            (None, None) => Mutation::Gaussian(moors::GaussianMutation::new(gene_rate, self.sigma)),
        }
    }

    /// The Gaussian step once `done` of `n` evaluations are spent.
    fn sigma_at(&self, done: usize, n: usize) -> f64 {
        let t = (done as f64 / n.max(1) as f64).min(1.0);
        self.sigma_end.map_or(self.sigma, |end| self.sigma * (end / self.sigma).powf(t))
    }
}

/// [`search`] with the optimiser's knobs `tuning`.
pub fn search_tuned(
    problem: &Problem,
    settings: Settings,
    tuning: Tuning,
    reference: Option<&[f64]>,
    cancel: Option<&AtomicBool>,
    on_progress: &OnBatch<'_>,
) -> Result<Outcome, ThudError> {
    problem.check()?;
    let n = settings.evaluations;
    let archive = Archive::new(problem, n, cancel, reference, on_progress);
    let look = |genes: &[Vec<f64>], cap: usize| -> Vec<Option<Candidate>> {
        let idx = archive.batch(genes, cap);
        let st = archive.state.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        idx.iter().map(|i| i.map(|i| st.1[i].clone())).collect()
    };
    let reference = || {
        let r = archive.reference.lock().unwrap_or_else(std::sync::PoisonError::into_inner).clone()?;
        Some(r.iter().zip(&problem.objectives).map(|(v, o)| if o.sense == Sense::Maximize { -v } else { *v }).collect())
    };
    run_moors(problem, tuning, n, settings.seed, &look, &reference)
        .map_err(|e| ThudError::invalid("--evaluations", e.0))?;
    let partial = archive.cancelled();
    Ok(archive.into_outcome(partial))
}

/// Why a told point could not be run, or why the optimiser stopped: the words to show.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct Failure(pub String);

/// The candidate of each row of genes (on [0, 1] of the whole box), the new points evaluated
/// while the evaluations stay within the cap given (at most the budget); None past it.
pub(super) type Look<'a> = dyn Fn(&[Vec<f64>], usize) -> Vec<Option<Candidate>> + 'a;

/// Every candidate the optimiser has been given, by index, with the genes (of the whole box)
/// it was first asked at.
type Seen = RefCell<BTreeMap<usize, (Vec<f64>, Candidate)>>;

/// A box of genes: each gene's `[lo, hi]` within [0, 1] of the whole box.
#[derive(Debug, Clone, PartialEq)]
struct GeneBox {
    lo: Vec<f64>,
    hi: Vec<f64>,
}

impl GeneBox {
    fn whole(nv: usize) -> GeneBox {
        GeneBox { lo: vec![0.0; nv], hi: vec![1.0; nv] }
    }
}

/// Runs the search's optimiser over `problem` for a budget of `n` evaluations, seeded by
/// `seed`: the one place it is built, for [`search`] and the ask/tell form alike, so both
/// follow the same phases. Without `tuning.narrow`, `moors`' algorithm over the whole box.
/// With it, two phases of the one budget: the algorithm over the whole box until a share of
/// the budget is spent, then again over the box the front found so far spans (widened by a
/// margin), its first population the front's designs; the front is the archive's over both.
/// `look` evaluates each batch; `reference` is the hypervolume's reference point (the
/// objectives minimised) once fixed, for the hypervolume-indicator survival. The error is
/// the sentence to show.
pub(super) fn run_moors(
    problem: &Problem,
    tuning: Tuning,
    n: usize,
    seed: u64,
    look: &Look<'_>,
    reference: &dyn Fn() -> Option<Vec<f64>>,
) -> Result<(), Failure> {
    let nv = problem.variables.len();
    let seen: Seen = RefCell::default();
    let whole = GeneBox::whole(nv);
    let sigma = Rc::new(Cell::new(tuning.sigma));
    let phase = Phase { problem, tuning, budget: n, sigma: &sigma, look, seen: &seen, reference };
    let Some(narrow) = tuning.narrow else {
        return phase.run(tuning.algorithm, n, n, seed, &whole, &[]);
    };
    let first = ((n as f64 * narrow.share).round() as usize).clamp(1, n);
    phase.run(tuning.algorithm, first, first, seed, &whole, &[])?;
    let (inner, start) = narrowed(problem, &seen.borrow(), narrow, tuning.population_for(n));
    let left = n.saturating_sub(seen.borrow().len());
    if left == 0 {
        return Ok(());
    }
    let start = if narrow.start_at_front { start } else { Vec::new() };
    phase.run(narrow.then, left, n, seed ^ 0x9e37_79b9_7f4a_7c15, &inner, &start)
}

/// The box around the front of the candidates `seen`: for each numeric variable the span of
/// the front's genes widened on each side by `narrow.margin` of the whole range and
/// `narrow.widen` of the span, within [0, 1]; a choice keeps all its options. With the front's
/// designs (their genes), at most `most` of them, evenly along the front. No front: the whole
/// box.
fn narrowed(
    problem: &Problem,
    seen: &BTreeMap<usize, (Vec<f64>, Candidate)>,
    narrow: Narrowing,
    most: usize,
) -> (GeneBox, Vec<Vec<f64>>) {
    let nv = problem.variables.len();
    let entries: Vec<&(Vec<f64>, Candidate)> = seen.values().collect();
    let all: Vec<Candidate> = entries.iter().map(|(_, c)| c.clone()).collect();
    let front: Vec<&Vec<f64>> = problem.front(&all).into_iter().map(|i| &entries[i].0).collect();
    let mut b = GeneBox::whole(nv);
    if front.is_empty() {
        return (b, Vec::new());
    }
    for (k, v) in problem.variables.iter().enumerate() {
        if matches!(v, Variable::Range { .. }) {
            let lo = front.iter().map(|g| g[k]).fold(f64::INFINITY, f64::min);
            let hi = front.iter().map(|g| g[k]).fold(f64::NEG_INFINITY, f64::max);
            let margin = narrow.margin + narrow.widen * (hi - lo);
            b.lo[k] = (lo - margin).clamp(0.0, 1.0);
            b.hi[k] = (hi + margin).clamp(0.0, 1.0);
            if b.hi[k] <= b.lo[k] {
                (b.lo[k], b.hi[k]) = (0.0, 1.0);
            }
        }
    }
    let start: Vec<Vec<f64>> = if front.len() <= most {
        front.into_iter().cloned().collect()
    } else {
        (0..most).map(|j| front[j * front.len() / most].clone()).collect()
    };
    (b, start)
}

/// One phase of a search: what every phase shares.
struct Phase<'a, 'l> {
    problem: &'a Problem,
    tuning: Tuning,
    /// The search's whole budget.
    budget: usize,
    /// The Gaussian step of the mutation, lowered as the budget is spent.
    sigma: &'a Rc<Cell<f64>>,
    look: &'a Look<'l>,
    seen: &'a Seen,
    reference: &'a dyn Fn() -> Option<Vec<f64>>,
}

impl Phase<'_, '_> {
    /// `algorithm` over the genes of `inner` (mapped onto [0, 1] for `moors`), its generations
    /// those a budget of `n` fills, its evaluations stopped at `cap` in all; its first
    /// population `start` (genes of the whole box), the rest drawn.
    fn run(
        &self,
        algorithm: Algorithm,
        n: usize,
        cap: usize,
        seed: u64,
        inner: &GeneBox,
        start: &[Vec<f64>],
    ) -> Result<(), Failure> {
        let whole = *inner == GeneBox::whole(inner.lo.len());
        let to_inner = |g: &Vec<f64>| -> Vec<f64> {
            g.iter()
                .enumerate()
                .map(|(k, &x)| ((x - inner.lo[k]) / (inner.hi[k] - inner.lo[k])).clamp(0.0, 1.0))
                .collect()
        };
        // A start design is asked at its own genes, not at their image mapped there and back.
        let starts: HashMap<Vec<u64>, Vec<f64>> =
            start.iter().map(|g| (to_inner(g).iter().map(|x| x.to_bits()).collect(), g.clone())).collect();
        let eval = |genes: &Array2<f64>| -> Vec<Option<Candidate>> {
            let rows: Vec<Vec<f64>> = genes
                .outer_iter()
                .map(|r| {
                    let r = r.to_vec();
                    if whole {
                        return r;
                    }
                    let bits: Vec<u64> = r.iter().map(|x| x.to_bits()).collect();
                    starts.get(&bits).cloned().unwrap_or_else(|| {
                        r.iter().enumerate().map(|(k, &x)| inner.lo[k] + x * (inner.hi[k] - inner.lo[k])).collect()
                    })
                })
                .collect();
            let found = (self.look)(&rows, cap);
            let mut seen = self.seen.borrow_mut();
            for (g, c) in rows.into_iter().zip(&found) {
                if let Some(c) = c {
                    seen.entry(c.index).or_insert_with(|| (g, c.clone()));
                }
            }
            self.sigma.set(self.tuning.sigma_at(seen.len(), self.budget));
            found
        };
        let objectives = &self.problem.objectives;
        let fitness = |g: &Array2<f64>| -> Array2<f64> {
            let found = eval(g);
            let mut out = Array2::from_elem((found.len(), objectives.len()), PENALTY);
            for (r, c) in found.iter().enumerate() {
                if let Some(m) = c.as_ref().and_then(|c| c.minimized(objectives)) {
                    for (k, v) in m.into_iter().enumerate() {
                        out[[r, k]] = v;
                    }
                }
            }
            out
        };
        let constraints = Constraints { eval: &eval, n_con: self.problem.constraints.len() + 1 };
        let sampler = Sampler { rows: start.iter().map(to_inner).collect(), start: self.tuning.start };
        let tuning = Tuning { algorithm, ..self.tuning };
        let mutation = tuning.mutation(self.problem.variables.len(), self.sigma);
        let parts = Parts { fitness, constraints, sampler, mutation };
        build_and_run(tuning, self.problem.variables.len(), n, seed, parts, self.reference)
    }
}

/// `moors`' algorithm `tuning.algorithm` with the search's operators over `nv` genes in
/// [0, 1], its generations those a budget of `n` fills, seeded by `seed`, its first population
/// from `sampler`.
fn build_and_run<F, G>(
    tuning: Tuning,
    nv: usize,
    n: usize,
    seed: u64,
    parts: Parts<F, G>,
    reference: &dyn Fn() -> Option<Vec<f64>>,
) -> Result<(), Failure>
where
    F: Fn(&Array2<f64>) -> Array2<f64>,
    G: moors::ConstraintsFn<Dim = ndarray::Ix2>,
{
    use moors::SimulatedBinaryCrossover;
    let Parts { fitness, constraints, sampler, mutation } = parts;
    let pop = tuning.population_for(n.max(sampler.rows.len()));
    // Offspring that copy a parent cost nothing (the cache): generations go on until the
    // budget is spent, at most three times as many as the budget would fill. A first
    // population given (designs already evaluated) costs nothing either.
    let kids = tuning.offspring_for(pop);
    let first = pop.saturating_sub(sampler.rows.len());
    let iterations = 3 * n.saturating_sub(first).div_ceil(kids).max(1);
    macro_rules! run {
        ($builder:ty $(, $selector:expr, $survivor:expr)?) => {{
            let mut ga = <$builder>::default()
                $(.selector($selector).survivor($survivor))?
                .fitness_fn(fitness)
                .constraints_fn(constraints)
                .sampler(sampler)
                .crossover(SimulatedBinaryCrossover::new(tuning.crossover_eta))
                .mutation(mutation)
                .duplicates_cleaner(Distinct(tuning.distinct))
                .num_vars(nv)
                .population_size(pop)
                .num_offsprings(kids)
                .num_iterations(iterations)
                .crossover_rate(0.9)
                .mutation_rate(tuning.mutation_rate)
                .seed(seed)
                .build()
                .map_err(|e| Failure(format!("the optimiser refused the problem: {e}")))?;
            ga.run().map_err(|e| Failure(format!("the optimiser failed: {e}")))
        }};
    }
    match tuning.algorithm {
        Algorithm::Nsga2 => run!(moors::Nsga2Builder<_, _, _, _, _>),
        Algorithm::Spea2 => run!(moors::Spea2Builder<_, _, _, _, _>),
        Algorithm::AgeMoea => run!(moors::AgeMoeaBuilder<_, _, _, _, _>),
        Algorithm::Ibea | Algorithm::Nsga2ThenIbea => {
            // The first population's survival, then half the generations the budget fills.
            let nsga2_calls =
                if tuning.algorithm == Algorithm::Ibea { 0 } else { 1 + n.saturating_sub(pop).div_ceil(kids) / 2 };
            let survivor = HypervolumeSurvival { reference, kappa: 0.05, nsga2_calls };
            let selector = moors::selection::moo::Nsga2RankAndScoringSelection::new();
            run!(moors::AlgorithmBuilder<_, _, _, _, _, _, _>, selector, survivor)
        }
    }
}

/// What a phase hands `moors` beside the settings: its evaluations, first population and
/// mutation.
struct Parts<F, G> {
    fitness: F,
    constraints: G,
    sampler: Sampler,
    mutation: Mutation,
}

/// The constraints of a batch for `moors` (≤ 0: met): each constraint's margin negated, then
/// one that is 0 for a point that ran with every objective defined.
struct Constraints<'e, E: Fn(&Array2<f64>) -> Vec<Option<Candidate>>> {
    eval: &'e E,
    n_con: usize,
}

impl<E: Fn(&Array2<f64>) -> Vec<Option<Candidate>>> moors::ConstraintsFn for Constraints<'_, E> {
    type Dim = ndarray::Ix2;

    fn call(&self, genes: &Array2<f64>) -> Array2<f64> {
        constraint_rows(&(self.eval)(genes), self.n_con)
    }

    fn lower_bound(&self) -> Option<f64> {
        Some(0.0)
    }

    fn upper_bound(&self) -> Option<f64> {
        Some(1.0)
    }
}

/// The constraint rows `moors` reads for a batch of candidates (None: a point over the
/// budget): each constraint's margin negated (≤ 0 is met), then one row that is 0 where the
/// design evaluated and every objective has a value; [`PENALTY`] where a value is missing.
fn constraint_rows(found: &[Option<Candidate>], n_con: usize) -> Array2<f64> {
    let mut out = Array2::from_elem((found.len(), n_con), PENALTY);
    for (r, c) in found.iter().enumerate() {
        let Some(c) = c else { continue };
        for (k, m) in c.margins.iter().enumerate() {
            out[[r, k]] = m.map_or(PENALTY, |m| -m);
        }
        let ok = c.error.is_none() && c.objectives.iter().all(Option::is_some);
        out[[r, n_con - 1]] = if ok { 0.0 } else { PENALTY };
    }
    out
}

/// The baseline of uniform random designs: `settings.evaluations` points, evaluated as
/// [`search`] evaluates them.
pub fn random_search(problem: &Problem, settings: Settings) -> Result<Outcome, ThudError> {
    problem.check()?;
    let mut rng = SplitMix64(settings.seed);
    let genes: Vec<Vec<f64>> =
        (0..settings.evaluations).map(|_| (0..problem.variables.len()).map(|_| rng.uniform()).collect()).collect();
    Ok(baseline(problem, settings.evaluations, &genes))
}

/// The baseline of a Latin hypercube of `settings.evaluations` points: each variable's range
/// cut in as many equal strata, one point in each, the strata shuffled per variable.
pub fn latin_hypercube(problem: &Problem, settings: Settings) -> Result<Outcome, ThudError> {
    problem.check()?;
    let n = settings.evaluations;
    let mut rng = SplitMix64(settings.seed);
    let mut genes = vec![vec![0.0; problem.variables.len()]; n];
    for k in 0..problem.variables.len() {
        let mut order: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let j = ((rng.uniform() * (i + 1) as f64) as usize).min(i);
            order.swap(i, j);
        }
        for (i, g) in genes.iter_mut().enumerate() {
            g[k] = (order[i] as f64 + rng.uniform()) / n as f64;
        }
    }
    Ok(baseline(problem, n, &genes))
}

fn baseline(problem: &Problem, n: usize, genes: &[Vec<f64>]) -> Outcome {
    let quiet = |_: Progress, _: &[Candidate], _: &[usize]| {};
    let archive = Archive::new(problem, n, None, None, &quiet);
    archive.batch(genes, n);
    archive.into_outcome(false)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    fn paper_problem() -> Problem {
        paper_problem_with(vec![])
    }

    /// The paper's Table 3 design searched over its ball's mass and clearance for a low peak
    /// level and a steep inclination, under `constraints`.
    pub(in crate::design) fn paper_problem_with(constraints: Vec<Constraint>) -> Problem {
        let base = Design::paper_table3().check().unwrap();
        Problem {
            base,
            variables: vec![
                Variable::parse_range("mass=20g:120g").unwrap(),
                Variable::parse_range("gap=1cm:6cm").unwrap(),
            ],
            objectives: vec![
                Objective::parse("spl_max_db", Sense::Minimize).unwrap(),
                Objective::parse("inclination_cm_s", Sense::Maximize).unwrap(),
            ],
            constraints,
            band_hz: vec![],
            robust: None,
        }
    }

    #[test]
    fn hypervolume_of_a_staircase_is_its_rectangles() {
        // Two points (1, 3) and (2, 1) against (4, 4): boxes of 3×1 and 2×3 sharing 2×1, so
        // 3 + 6 − 2 = 7; a dominated point and one beyond the reference add nothing.
        let hv = hypervolume_2d(&[[1.0, 3.0], [2.0, 1.0], [3.0, 3.5], [5.0, 0.0]], [4.0, 4.0]);
        assert!((hv - 7.0).abs() < 1e-12, "{hv}");
        assert_eq!(hypervolume_2d(&[], [1.0, 1.0]), 0.0);
    }

    #[test]
    fn columns_are_the_sweep_columns() {
        let sweep: Vec<&str> = crate::schema::SWEEP.columns.iter().map(|c| c.name).collect();
        for (c, name) in COLUMNS.iter().filter(|(c, _)| !c.forced()) {
            assert!(sweep.contains(name), "{name} is not a sweep column");
            assert_eq!(Column::named(name), Some(*c));
        }
    }

    #[test]
    fn parsing_names_what_was_typed() {
        let e = Variable::parse_range("mass=120g:20g").unwrap_err();
        assert_eq!(e.param(), "--vary mass");
        let e = Variable::parse_range("nope=1:2").unwrap_err();
        assert!(e.to_string().contains("nope"), "{e}");
        let e = Variable::parse_choice("sphere=steel,unobtainium").unwrap_err();
        assert!(e.to_string().contains("unobtainium"), "{e}");
        let e = Objective::parse("spl", Sense::Minimize).unwrap_err();
        assert_eq!(e.param(), "--minimize");
        let c = Constraint::parse("mass<=60g").unwrap();
        assert!((c.value - 0.06).abs() < 1e-15 && c.at_most);
        let c = Constraint::parse("spl_max_db >= 90").unwrap();
        assert!(!c.at_most && c.value == 90.0);
        assert!(Constraint::parse("spl_max_db=90").is_err());
        // A bound that is no finite number is refused naming the flag, for a parameter as for a
        // result column.
        for bad in ["mass>=nan", "mass<=inf", "mass<=-inf", "gap<=NaN", "spl_max_db<=nan", "spl_max_db>=inf"] {
            let e = Constraint::parse(bad).unwrap_err().to_string();
            assert!(e.contains("--require") && e.contains(bad), "{bad}: {e}");
        }
    }

    #[test]
    fn a_point_is_the_study_cell_at_its_values() {
        let p = paper_problem();
        let values = p.decode(&[0.3, 0.4]);
        let c = p.evaluate(0, values.clone(), None);
        let (Value::Number(m), Value::Number(g)) = (&values[0], &values[1]) else { panic!() };
        let grid = study::Grid::new(
            p.base.clone(),
            vec![
                study::Vary::of_values("mass", &[*m], Spelling::Flag).unwrap(),
                study::Vary::of_values("gap", &[*g], Spelling::Flag).unwrap(),
            ],
            Spelling::Flag,
        )
        .unwrap();
        let cell = &study::sweep(&grid, None, &|_, _| {}).unwrap().cells[0];
        assert_eq!(c.objectives, vec![cell.metrics.spl_max_db, cell.metrics.inclination_cm_s]);
    }

    #[test]
    fn the_search_is_the_same_for_a_seed_and_keeps_its_budget() {
        let p = paper_problem();
        let s = Settings { evaluations: 60, seed: 7 };
        let a = search(&p, s, None, None, &|_, _, _| {}).unwrap();
        let b = search(&p, s, None, None, &|_, _, _| {}).unwrap();
        assert!(a.all.len() <= 60 && a.all.len() > 40, "{}", a.all.len());
        assert_eq!(a.all, b.all);
        assert_eq!(a.front, b.front);
        let c = search(&p, Settings { seed: 8, ..s }, None, None, &|_, _, _| {}).unwrap();
        assert_ne!(a.all, c.all);
        // Every front point is feasible and no evaluated feasible point dominates it.
        for &i in &a.front {
            let fi = a.all[i].minimized(&p.objectives).unwrap();
            assert!(a
                .all
                .iter()
                .filter(|c| c.feasible())
                .all(|c| !dominates(&c.minimized(&p.objectives).unwrap(), &fi)));
        }
    }

    #[test]
    fn a_search_in_two_phases_keeps_its_budget_and_searches_the_box_around_the_first_front() {
        let p = paper_problem();
        let narrow = Narrowing { share: 0.5, margin: 0.05, widen: 0.0, then: Algorithm::Nsga2, start_at_front: true };
        let tuning = Tuning { narrow: Some(narrow), ..Tuning::default() };
        let s = Settings { evaluations: 80, seed: 3 };
        let a = search_tuned(&p, s, tuning, None, None, &|_, _, _| {}).unwrap();
        let b = search_tuned(&p, s, tuning, None, None, &|_, _, _| {}).unwrap();
        assert_eq!(a.all, b.all);
        assert_eq!(a.all.len(), 80);
        // The first phase spends its half over the whole box; every later design lies in the
        // box its front spans, widened by 5 % of each range.
        let genes = |c: &Candidate| -> Vec<f64> {
            c.values
                .iter()
                .zip(&p.variables)
                .map(|(v, var)| match (v, var) {
                    (Value::Number(x), Variable::Range { lo, hi, .. }) => (x - lo) / (hi - lo),
                    _ => panic!("numeric"),
                })
                .collect()
        };
        let first: BTreeMap<usize, (Vec<f64>, Candidate)> =
            a.all[..40].iter().map(|c| (c.index, (genes(c), c.clone()))).collect();
        let (inner, start) = narrowed(&p, &first, narrow, 8);
        assert!(!start.is_empty() && start.len() <= 8);
        assert!(inner.hi[1] - inner.lo[1] < 1.0, "the front's gaps span less than the range: {inner:?}");
        for c in &a.all[40..] {
            let g = genes(c);
            for (k, x) in g.iter().enumerate() {
                assert!(*x >= inner.lo[k] - 1e-12 && *x <= inner.hi[k] + 1e-12, "{:?} outside {inner:?}", c.values);
            }
        }
        // The front is the archive's over both phases.
        assert_eq!(a.front, p.front(&a.all));
    }

    #[test]
    fn a_shrinking_step_goes_from_sigma_to_its_end_geometrically() {
        let t = Tuning { sigma: 0.2, sigma_end: Some(0.05), ..Tuning::default() };
        assert!((t.sigma_at(0, 400) - 0.2).abs() < 1e-15);
        assert!((t.sigma_at(200, 400) - 0.1).abs() < 1e-12);
        assert!((t.sigma_at(400, 400) - 0.05).abs() < 1e-12);
        assert!((t.sigma_at(900, 400) - 0.05).abs() < 1e-12, "past the budget it stays at its end");
        assert_eq!(Tuning::default().sigma_at(200, 400), 0.1);
    }

    #[test]
    fn robust_mode_takes_each_result_at_the_ensembles_percentile_on_its_worse_side() {
        // Q = 0.9 over 10 ball offsets: SPLmax (minimised) at the ensemble's p90, e
        // (maximised) at its p10, both by the ensemble's own nearest-rank percentiles.
        let mut p = paper_problem();
        p.robust = Some(Robust::new(10, 0.9).unwrap());
        p.constraints = vec![Constraint::parse("spl_max_db<=200").unwrap()];
        let values = p.decode(&[0.5, 0.3]);
        let c = p.evaluate(0, values.clone(), None);
        let e = crate::ensemble::evaluate(&p.design_at(&values).unwrap(), 10, None).unwrap().unwrap();
        assert_eq!(c.objectives, vec![e.spread.spl_max_db.p90, e.spread.inclination_cm_s.p10]);
        assert_eq!(c.margins, vec![e.spread.spl_max_db.p90.map(|v| 200.0 - v)]);
        // The median is the ensemble's median; p10 ≤ median ≤ p90, and the spread is real.
        p.robust = Some(Robust::new(10, 0.5).unwrap());
        let m = p.evaluate(0, values, None);
        assert_eq!(m.objectives, vec![e.spread.spl_max_db.median, e.spread.inclination_cm_s.median]);
        assert!(c.objectives[0].unwrap() >= m.objectives[0].unwrap());
        assert!(c.objectives[1].unwrap() <= m.objectives[1].unwrap());
        assert!(Robust::new(4, 0.0).is_err() && Robust::new(4, 1.5).is_err() && Robust::new(0, 0.5).is_err());
        assert_eq!(Robust::new(10, 0.7).unwrap().rank(10, true), 7);
        assert_eq!(Robust::new(10, 1.0).unwrap().rank(10, false), 1);
    }

    #[test]
    fn with_four_variables_the_median_over_ten_seeds_beats_random_search_and_a_latin_hypercube() {
        // Mass, gap, contact damping c1 and the ball's material; 400 evaluations a search, ten
        // seeds, each method's hypervolume against one fixed reference point (110 dB, 0 cm/s).
        // 12,000 designs in all: about 25 s on 2 busy cores in release. (At 150 evaluations
        // a Latin hypercube wins: docs/model.md, "Design search".)
        let mut p = paper_problem();
        p.variables.push(Variable::parse_range("c1=10:60").unwrap());
        p.variables.push(Variable::parse_choice("sphere=steel,acrylic,nylon").unwrap());
        let reference = [110.0, 0.0];
        let hv = |o: &Outcome| p.hypervolume(&o.all, &o.front, &reference).unwrap();
        let median = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            0.5 * (v[4] + v[5])
        };
        let (mut nsga, mut random, mut lhs) = (Vec::new(), Vec::new(), Vec::new());
        for seed in 1..=10 {
            let s = Settings { evaluations: 400, seed };
            let o = search(&p, s, Some(&reference), None, &|_, _, _| {}).unwrap();
            // At most the budget (a generation of copies of parents costs nothing, so a search
            // may end below it: then it is the one with fewer designs).
            assert!(o.all.len() <= 400, "seed {seed}: {} designs", o.all.len());
            nsga.push(hv(&o));
            random.push(hv(&random_search(&p, s).unwrap()));
            lhs.push(hv(&latin_hypercube(&p, s).unwrap()));
        }
        eprintln!("hypervolumes by seed: NSGA-II {nsga:.3?}\nrandom {random:.3?}\nLHS {lhs:.3?}");
        let (n, r, l) = (median(nsga), median(random), median(lhs));
        eprintln!("medians: NSGA-II {n:.4}, random {r:.4}, LHS {l:.4}");
        assert!(n > r && n > l, "NSGA-II {n} against random {r} and LHS {l}");
    }

    #[test]
    fn a_constraint_is_met_by_every_front_design_or_named_when_none_can() {
        let mut p = paper_problem();
        p.constraints = vec![Constraint::parse("mass<=60g").unwrap()];
        let o = search(&p, Settings { evaluations: 40, seed: 1 }, None, None, &|_, _, _| {}).unwrap();
        assert!(!o.front.is_empty());
        for &i in &o.front {
            let Value::Number(m) = o.all[i].values[0] else { panic!() };
            assert!(m <= 0.06 && o.all[i].margins[0].unwrap() >= 0.0);
        }
        p.constraints = vec![Constraint::parse("mass<=60g").unwrap(), Constraint::parse("spl_max_db<=10").unwrap()];
        let o = search(&p, Settings { evaluations: 24, seed: 1 }, None, None, &|_, _, _| {}).unwrap();
        assert!(o.front.is_empty());
        let (k, best) = p.binding(&o.all).unwrap();
        assert_eq!(k, 1);
        assert!(best < 0.0);
    }
}
