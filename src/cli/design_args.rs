//! The design flags shared by `simulate`, `sweep` and `export`: a preset, then overrides.

use clap::builder::{PossibleValue, PossibleValuesParser};
use clap::{Arg, ArgAction, ArgGroup, ArgMatches, Args, Command, FromArgMatches};

use super::{CliError, Ctx};
use crate::design::{Design, ValidDesign};
use crate::error::ThudError;
use crate::limits::{self, short, Range, Refusal, Remedy};
use crate::params::{self, Accepts, Group, Input, Param, Spelling};
use crate::presets;
use crate::units::Kind;

/// The force amplitude F0 is `--force-amplitude` on every command: `--force` replaces an output
/// file wherever a command writes one. `F` says whether the command has a `--force` of its own
/// ([`ForceAmplitude`]) or not ([`Force`]: then `--force`, the amplitude's name before, is
/// refused with a line naming `--force-amplitude`).
pub trait ForceFlag: Clone + std::fmt::Debug {
    /// Whether `--force` is the old spelling of the amplitude here (refused, naming the new one).
    const OLD_SPELLING: bool;
}

/// A command without a file to replace: `--force-amplitude F0`, and `--force` refused with a
/// line naming `--force-amplitude`.
#[derive(Debug, Clone)]
pub struct Force;

impl ForceFlag for Force {
    const OLD_SPELLING: bool = true;
}

/// A command whose own `--force` replaces a file: `--force-amplitude F0` alone.
#[derive(Debug, Clone)]
pub struct ForceAmplitude;

impl ForceFlag for ForceAmplitude {
    const OLD_SPELLING: bool = false;
}

pub use super::errors::{flag_of, FORCE_AMPLITUDE};

/// The clap id of the old spelling `--force` where it is refused ([`Force`]).
const OLD_FORCE: &str = "old_force_spelling";

/// Which rows of the engine's table [`params::DESIGN`] a command takes as flags.
pub trait Rows: Clone + std::fmt::Debug {
    /// Whether the row `name` is a flag of the command.
    fn takes(name: &str) -> bool;
}

/// Every row: the commands that run a design.
#[derive(Debug, Clone)]
pub struct AllRows;

impl Rows for AllRows {
    fn takes(_: &str) -> bool {
        true
    }
}

/// The rows a fit of c1 reads: the structure, the ball and its contact, the strike's speed
/// and how the runs are computed. Not c1 (fitted), the run's length (the record's), the force,
/// the ball's start (the fit spreads it), the listener or the zones.
#[derive(Debug, Clone)]
pub struct FitRows;

/// The rows of [`FitRows`].
pub const FIT_ROWS: &[&str] = &[
    "mass",
    "gap",
    "v0",
    "main-mass",
    "k",
    "c",
    "k-hz",
    "sphere",
    "plate",
    "sphere-poisson",
    "density",
    "radius",
    "no-tension",
    "solver",
    "dt",
];

impl Rows for FitRows {
    fn takes(name: &str) -> bool {
        FIT_ROWS.contains(&name)
    }
}

/// A design: a preset, then any flag given explicitly overrides the preset's value. The flags
/// are the rows of the engine's table [`params::DESIGN`] (name, placeholder, help, choices,
/// relations): [`Args::augment_args`] builds them from it and [`FromArgMatches`] reads them
/// back, so there is no hand-kept list of flags here.
#[derive(Debug, Clone)]
pub struct DesignArgs<F: ForceFlag = Force, R: Rows = AllRows> {
    /// `--preset`.
    preset: String,
    /// `--design`: a design file or a saved design's name, instead of the preset.
    design: Option<String>,
    /// The design flags given, as (row name, value) in table order; the force amplitude under
    /// its flag's name (`force-amplitude`).
    given: Vec<(String, Input)>,
    /// `--force` where it is the amplitude's old spelling ([`Force`]), as typed (empty: no value).
    old_force: Option<String>,
    force: std::marker::PhantomData<(F, R)>,
}

/// The clap id of a row (its name with underscores, as clap's derive spells field names).
fn id(name: &str) -> String {
    name.replace('-', "_")
}

/// The flag of one row of the engine's table (the force amplitude as `--force-amplitude`).
fn flag(p: &Param<params::DesignDraft>) -> Arg {
    let (long, alias) = match (p.name, p.alias) {
        ("force", _) => (FORCE_AMPLITUDE, None),
        (name, alias) => (name, alias),
    };
    table_flag(p, long, alias, false)
}

/// The flag `--{long}` (with the visible alias `alias`) of one row `p` of one of the engine's
/// tables ([`params::DESIGN`], [`params::PULSE`]): its help, placeholder, conflicts and what it
/// accepts, all from the row. `names_take_hyphens`: a name (a material) may start with `-`
/// (then the engine refuses it naming the flag, as `thud pulse` has always done).
pub(crate) fn table_flag<T>(
    p: &Param<T>,
    long: &'static str,
    alias: Option<&'static str>,
    names_take_hyphens: bool,
) -> Arg {
    let mut arg = Arg::new(id(long)).long(long).help(p.help).required(false);
    if let Some(alias) = alias {
        arg = arg.visible_alias(alias);
    }
    if !p.value_name.is_empty() {
        arg = arg.value_name(p.value_name);
    }
    if let Some(c) = p.conflicts {
        arg = arg.conflicts_with_all(c.with.iter().map(|w| id(w)));
    }
    // No clap `requires` for `p.requires`: clap's message names only the flag missing; the
    // engine's ([`params::design`]) names both, as Python's does.
    match &p.accepts {
        Accepts::Switch { .. } => arg.action(ArgAction::SetTrue),
        Accepts::Choice { names, helps, .. } => {
            let values = names.iter().enumerate().map(|(i, n)| match helps.get(i) {
                Some(h) => PossibleValue::new(*n).help(*h),
                None => PossibleValue::new(*n),
            });
            // The placeholder clap's derive gives a choice: the id in capitals (`QUAD_SIGNS`).
            arg.action(ArgAction::Set)
                .value_name(id(p.name).to_uppercase())
                .value_parser(PossibleValuesParser::new(values))
        }
        Accepts::Quantity { .. } | Accepts::Count { .. } => {
            arg.action(ArgAction::Set).allow_hyphen_values(true).value_parser(clap::value_parser!(String))
        }
        Accepts::Name { .. } => {
            arg.action(ArgAction::Set).allow_hyphen_values(names_take_hyphens).value_parser(clap::value_parser!(String))
        }
    }
}

/// The value given to the flag `--{long}` of the row `p` ([`table_flag`]), if it was given.
pub(crate) fn table_value<T>(p: &Param<T>, m: &ArgMatches, long: &str) -> Option<Input> {
    match p.accepts {
        Accepts::Switch { .. } => m.get_flag(&id(long)).then_some(Input::Switch(true)),
        _ => m.get_one::<String>(&id(long)).map(|t| Input::Text(t.clone())),
    }
}

/// The row's long flag (the force amplitude's is `--force-amplitude`).
fn long(p: &Param<params::DesignDraft>) -> &'static str {
    if p.name == "force" {
        FORCE_AMPLITUDE
    } else {
        p.name
    }
}

impl<F: ForceFlag, R: Rows> Args for DesignArgs<F, R> {
    fn augment_args(cmd: Command) -> Command {
        let preset = Arg::new("preset")
            .long("preset")
            .value_name("P")
            .default_value("default")
            .action(ArgAction::Set)
            .value_parser(clap::value_parser!(String))
            .help("Starting design (`thud presets` lists them: default, paper-fig9, paper-table3, quiet-nylon, …)");
        let design = Arg::new("design")
            .long("design")
            .value_name("FILE")
            .action(ArgAction::Set)
            .value_parser(clap::value_parser!(String))
            .conflicts_with("preset")
            .help(DESIGN_HELP);
        let rows = || params::DESIGN.iter().filter(|p| R::takes(p.name));
        let ids = ["preset".to_string(), "design".to_string()].into_iter().chain(rows().map(|p| id(long(p))));
        let cmd = cmd.group(ArgGroup::new("DesignArgs").multiple(true).args(ids)).arg(preset).arg(design);
        let cmd = rows().fold(cmd, |cmd, p| cmd.arg(flag(p)));
        if !F::OLD_SPELLING || !R::takes("force") {
            return cmd;
        }
        // The amplitude's old name, kept only to say the new one (hidden from help).
        cmd.arg(
            Arg::new(OLD_FORCE)
                .long("force")
                .hide(true)
                .num_args(0..=1)
                .allow_hyphen_values(true)
                .action(ArgAction::Set)
                .value_parser(clap::value_parser!(String)),
        )
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl<F: ForceFlag, R: Rows> FromArgMatches for DesignArgs<F, R> {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let preset = m.get_one::<String>("preset").cloned().unwrap_or_else(|| "default".to_string());
        let design = m.get_one::<String>("design").cloned();
        let mut given = Vec::new();
        for p in params::DESIGN.iter().filter(|p| R::takes(p.name)) {
            let name = long(p);
            given.extend(table_value(p, m, name).map(|v| (name.to_string(), v)));
        }
        let old_force = if F::OLD_SPELLING && m.contains_id(OLD_FORCE) {
            Some(m.get_one::<String>(OLD_FORCE).cloned().unwrap_or_default())
        } else {
            None
        };
        Ok(DesignArgs { preset, design, given, old_force, force: std::marker::PhantomData })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl<F: ForceFlag, R: Rows> DesignArgs<F, R> {
    /// The design these flags describe, validated: each flag against its range (the error
    /// names the flag as typed), then the whole design (preset values too) and its derived
    /// quantities. The mapping from flags to the design is the engine's ([`params::design`]),
    /// shared with the Python module.
    pub fn design(&self) -> Result<ValidDesign, ThudError> {
        params::design(self.base()?, &self.given, Spelling::Flag).map_err(|e| self.named_as_file(e))
    }

    /// A value out of range that the `--design` file holds (no flag typed it) is named as the
    /// file's: "invalid --design: rig.toml: invalid --duration: 1e300 s is out of range; …".
    fn named_as_file(&self, e: ThudError) -> ThudError {
        match (&self.design, &e) {
            (Some(file), ThudError::OutOfRange { param, .. }) if !self.has(param.trim_start_matches("--")) => {
                ThudError::invalid("--design", format!("{file}: {e}"))
            }
            _ => e,
        }
    }

    /// The design these flags describe for a study that varies `varied`: as [`Self::design`],
    /// except that a varied frequency supplies the one a force needs (`--vary f=3Hz:8Hz:200`
    /// with a force and no `--freq`: the study sets every value anyway, the first stands in).
    pub fn design_over(&self, varied: &[&crate::study::Vary]) -> Result<ValidDesign, ThudError> {
        let first_freq = varied.iter().find(|v| v.name() == "freq").and_then(|v| v.values.first());
        match (self.design(), first_freq) {
            (Err(e), Some(&f)) if e.param() == "--freq" && !self.has("freq") => {
                let mut given = self.given.clone();
                given.push(("freq".into(), Input::Num(f)));
                params::design(self.base()?, &given, Spelling::Flag)
            }
            (d, _) => d,
        }
    }

    /// The starting design: the `--design` file as it is, else the preset with the user's
    /// settings (its thresholds and its `[design]` defaults). Refuses `--force` where it is the
    /// amplitude's old spelling, naming `--force-amplitude`.
    fn base(&self) -> Result<Design, ThudError> {
        if let Some(typed) = &self.old_force {
            // `--force --json`: the next flag taken as the value is no amplitude.
            let typed = if typed.starts_with("--") { "" } else { typed.as_str() };
            let shown = super::errors::cut_chars(typed, 20);
            let what = if shown.is_empty() { String::new() } else { format!("{shown}: ") };
            let value = if shown.is_empty() { "F0" } else { shown.as_str() };
            return Err(ThudError::invalid(
                "--force",
                format!(
                    "{what}the force amplitude is --force-amplitude now (--force replaces an output file); \
                     give --force-amplitude {value}"
                ),
            ));
        }
        if let Some(text) = &self.design {
            return load_design(text);
        }
        let mut d = presets::preset(&self.preset)?;
        let settings = super::settings::load();
        d.thresholds = settings.thresholds(d.thresholds);
        // `--no-limit` lifts the solvers' own caps too.
        d.damper.no_limit = super::budget::no_limit();
        settings.design(d)
    }

    /// The design of a frequency response from these flags and its frequencies: `freqs_hz`
    /// as given, else the engine's default band of the design ([`params::response_setup`]).
    pub fn response_setup(&self, freqs_hz: Option<Vec<f64>>) -> Result<(ValidDesign, Vec<f64>), ThudError> {
        params::response_setup(self.base()?, &self.given, Spelling::Flag, freqs_hz, FORCE_AMPLITUDE)
    }

    /// The text typed for the row `name` (as in the table; the force under either name).
    fn text(&self, name: &str) -> Option<String> {
        self.given.iter().find_map(|(n, v)| match v {
            Input::Text(t) if n == name || (name == "force" && n == FORCE_AMPLITUDE) => Some(t.clone()),
            _ => None,
        })
    }

    /// Takes the uncertainty (`±…`, `+-…`) off the value typed for the row `name`, if one was
    /// typed with it: the whole text as typed; the design then reads the value alone.
    pub(crate) fn take_uncertainty(&mut self, name: &str) -> Option<String> {
        self.given.iter_mut().find_map(|(n, v)| match v {
            Input::Text(t) if n == name => {
                let (value, u) = crate::units::split_uncertainty(t);
                u?;
                let whole = t.clone();
                *t = value.to_string();
                Some(whole)
            }
            _ => None,
        })
    }

    /// The relative standard uncertainties the `--design` file carries (a fitted structure's),
    /// by row name, without those of the rows typed here (a typed value replaces the file's).
    pub(crate) fn file_uncertainty(&self) -> Vec<(String, f64)> {
        let Some(text) = &self.design else { return Vec::new() };
        let Ok(file) = crate::store::load_named_design(text) else { return Vec::new() };
        file.uncertainty.into_iter().filter(|(name, _)| !self.has(name)).collect()
    }

    /// Whether the row `name` was given.
    pub(crate) fn has(&self, name: &str) -> bool {
        self.text(name).is_some()
    }

    /// Whether the row `name` was typed in any form (a value or a switch such as `--settle`).
    pub(crate) fn typed_row(&self, name: &str) -> bool {
        self.given.iter().any(|(n, _)| n == name)
    }

    /// The numeric flags the user typed that change the run (not the listener's or the
    /// study's), as `--name value`, for messages about the design as a whole.
    pub(crate) fn typed(&self) -> String {
        let typed: Vec<String> = params::DESIGN
            .iter()
            .filter(|p| p.range().is_some() && !matches!(p.group, Group::Listener | Group::Study))
            .filter_map(|p| self.text(p.name).map(|t| format!("--{} {}", long(p), super::errors::cut_chars(&t, 20))))
            .collect();
        typed.join(", ")
    }

    /// `--duration` as typed, if it was.
    pub(crate) fn duration_text(&self) -> Option<String> {
        self.text("duration")
    }

    /// Refuses `--ensemble N` (N > 1) with `--ball-position`: the ensemble sets the offsets
    /// ([`params::check_ensemble`]).
    pub(crate) fn check_ensemble(&self, runs: usize) -> Result<(), ThudError> {
        params::check_ensemble(runs, self.has("ball-position"), Spelling::Flag)
    }

    /// What to show for a flag in a refusal: what the user typed, else the design's value.
    fn shown(&self, name: &str, value: f64, unit: &str) -> String {
        self.text(name).unwrap_or_else(|| format!("{} {unit}", short(value)))
    }

    /// Whether the row `name` was set by the user: as a flag, or as a key of the config's
    /// `[design]` (a refusal blames what the user set, wherever they set it).
    fn set(&self, name: &str) -> bool {
        self.has(name) || self.config_key(name).is_some()
    }

    /// The config's `[design]` key that set the row `name` ([`from_config`]); none with
    /// `--design`, which the config's defaults do not change.
    fn config_key(&self, name: &str) -> Option<String> {
        self.design.is_none().then(|| from_config(name)).flatten()
    }

    /// The engine's refusal ([`limits::check_run`] and the like) in the command line's words:
    /// "`--flag value`: estimate exceeds the limit; hint, or add --no-limit". `counted` names
    /// the flag and value of what the caller counts (`--samples 5`, `--masses/--gaps 20 × 20`,
    /// `--ensemble 16`).
    fn refuse(&self, ctx: &Ctx, d: &Design, r: Result<(), Refusal>, counted: (&str, &str)) -> Result<(), CliError> {
        let Err(r) = r else { return Ok(()) };
        let (flag, value) = match limits::refused_value(d, r.param) {
            // Set in the config only: named as its key there.
            Some((v, unit)) if !self.has(r.param) && self.config_key(r.param).is_some() => {
                let key = self.config_key(r.param).unwrap_or_default();
                (format!("{key} in {} [design]", crate::config::CONFIG_FILE), format!("{} {unit}", short(v)))
            }
            Some((v, unit)) => (format!("--{}", flag_of(r.param)), self.shown(r.param, v, unit)),
            None => (counted.0.to_string(), counted.1.to_string()),
        };
        let hint = hint(&r, counted.0);
        ctx.enforce(r.estimate, &flag, &value, &hint)
    }

    /// Refuses one run of `d` whose work is over a cap ([`limits::check_run`]), naming the
    /// flag that drives it; `samples_flag` is the flag that asked for `history_samples`.
    pub(crate) fn check_run(
        &self,
        ctx: &Ctx,
        d: &ValidDesign,
        history_samples: usize,
        samples_flag: &str,
    ) -> Result<(), CliError> {
        let r = limits::check_run(d, &|n| self.set(n), history_samples);
        self.refuse(ctx, d, r, (samples_flag, &history_samples.to_string()))
    }

    /// Refuses a design chart of `n_masses` × `n_gaps` cells of `d` whose work is over a cap
    /// ([`limits::check_sweep`]).
    pub(crate) fn check_sweep(
        &self,
        ctx: &Ctx,
        d: &ValidDesign,
        n_masses: usize,
        n_gaps: usize,
    ) -> Result<(), CliError> {
        let r = limits::check_sweep(d, &|n| self.set(n), n_masses, n_gaps);
        self.refuse(ctx, d, r, ("--masses/--gaps", &format!("{n_masses} × {n_gaps}")))
    }

    /// Refuses a study over `grid` (`--vary`, repeatable) whose work is over a cap
    /// ([`crate::study::check_grid`]: the product of every axis, each point's run and their sum).
    pub(crate) fn check_study(&self, ctx: &Ctx, grid: &crate::study::Grid) -> Result<(), CliError> {
        let r = crate::study::check_grid(grid, &|n| self.has(n));
        let shape: Vec<String> = grid.shape().iter().map(ToString::to_string).collect();
        self.refuse(ctx, &grid.base, r, ("--vary", &shape.join(" × ")))
    }

    /// Refuses a search's work ([`crate::design::search::check_work`]), naming `counted`.
    pub(crate) fn refuse_work(
        &self,
        ctx: &Ctx,
        d: &Design,
        r: Result<(), Refusal>,
        counted: (&str, &str),
    ) -> Result<(), CliError> {
        self.refuse(ctx, d, r, counted)
    }

    /// Refuses `cells` cells of `d` with `runs` ensemble runs each (a chart, a chart's part, or
    /// one design with `cells` = 1) whose work is over a cap ([`limits::check_runs`]); the
    /// runs are named by `flag` typed as `value`.
    pub(crate) fn check_runs(
        &self,
        ctx: &Ctx,
        d: &ValidDesign,
        cells: usize,
        runs: usize,
        flag: &str,
        value: &str,
    ) -> Result<(), CliError> {
        let r = limits::check_runs(d, &|n| self.set(n), cells, runs);
        self.refuse(ctx, d, r, (flag, value))
    }
}

/// The help of `--design` (on every command that takes a design).
pub const DESIGN_HELP: &str = "Starting design from a design file (what `thud fit … --save FILE.toml` and the explorer's save write) or a saved design's name, instead of --preset; flags override it";

/// The design `--design text` names ([`crate::store::load_named_design`], the loader of the
/// explorer's saved designs), its errors naming `--design`.
pub fn load_design(text: &str) -> Result<Design, ThudError> {
    use crate::store::StoreError;
    crate::store::load_named_design(text).map(|f| f.design).map_err(|e| match e {
        StoreError::Thud(e) => e.renamed("design"),
        StoreError::Io { source, .. }
            if source.kind() == std::io::ErrorKind::NotFound && !crate::store::names_a_file(text) =>
        {
            ThudError::invalid(
                "design",
                format!("no file '{text}' and no saved design of that name (a file is named with its path or .toml)"),
            )
        }
        e => ThudError::invalid("design", e.to_string()),
    })
}

/// The key of the config's `[design]` that sets the row `name` (by its name or alias), if any.
fn from_config(name: &str) -> Option<String> {
    let row = params::design_param(name)?;
    super::settings::load().design.keys().find(|k| k.as_str() == row.name || Some(k.as_str()) == row.alias).cloned()
}

/// What to change to bring a refused run under its cap, in the command line's words;
/// `counted` is the flag of what the caller counts (`--samples`).
pub(crate) fn hint(r: &Refusal, counted: &str) -> String {
    let per = &r.per;
    match r.remedy {
        Remedy::ShorterDuration { max_s } => format!("use --duration ≤ {} s{per}", short(max_s)),
        Remedy::ShorterDurationOrLargerDt { max_s } => {
            format!("use --duration ≤ {} s{per} or a larger --dt", short(max_s))
        }
        Remedy::LargerDtOrShorterDuration { min_s } => {
            format!("use --dt ≥ {} s{per} or a shorter --duration", short(min_s))
        }
        Remedy::FewerSamples { max } => format!("use {counted} ≤ {}", short(max)),
        Remedy::FewerCells { max } => format!("use fewer values N on either axis (product ≤ {})", short(max)),
        Remedy::ShorterDurationOrFewerCells { max_s } => {
            format!("use --duration ≤ {} s{per} or fewer cells", short(max_s))
        }
        Remedy::FewerRuns { max, cells, runs } if cells > 1 => {
            format!("use fewer runs ({cells} cells × {runs}; at most {} runs), e.g. more shards", short(max))
        }
        Remedy::FewerRuns { max, .. } => format!("use at most {} runs", short(max)),
        Remedy::ShorterDurationOrFewerRuns { max_s } => {
            format!("use --duration ≤ {} s{per} or fewer runs", short(max_s))
        }
        Remedy::FewerRunsPerFrequency { max } => {
            format!("use fewer runs (at most {} for these frequencies)", short(max))
        }
        Remedy::FewerFrequencies => "use fewer frequencies or a shorter --duration".to_string(),
        Remedy::LowerFrequencies => "use lower frequencies or a shorter --duration".to_string(),
        Remedy::EventSolverOrLargerDt => "use the event solver or a larger --dt".to_string(),
    }
}

/// Parses a range "FROM:TO:N" of quantities of `kind` (e.g. "30g:100g:20") for flag `--{name}`;
/// both ends are checked against `range`, N against [`limits::GRID_N`] ([`params::parse_range`]).
pub fn parse_range(name: &str, text: &str, kind: Kind, range: &Range) -> Result<Vec<f64>, ThudError> {
    params::parse_range(&format!("--{name}"), text, kind, range)
}
