//! The command-line front end: parses arguments (units at the edge), calls the engine and
//! prints text, JSON or CSV. No physics here.

mod basins;
mod bifurcation;
mod budget;
mod continuation;
mod design;
pub mod design_args;
mod errors;
mod export;
mod figure_out;
mod fit;
#[doc(hidden)]
pub use fit::series_from_text as fit_record_from_text;
mod format;
mod impact_map;
mod merge;
mod orbit;
mod output;
mod paper;
mod presets;
mod pulse;
mod response;
mod restitution;
mod settings;
mod shell;
mod simulate;
mod study;
mod sweep;
mod tui;

use clap::{Args, CommandFactory, Parser, Subcommand};

use crate::error::ThudError;
use crate::limits::Range;
use crate::units::{self, Kind};

pub use budget::Ctx;
pub use errors::CliError;
pub use format::OutputFormat;
pub use output::{check_finite, Out};

/// thud — design single-unit impact dampers: Hertz contact, impact noise and a live explorer.
///
/// Plain numbers are SI units (kg, m, m/s, N/m^1.5, Pa·s/m) except angles, which are degrees.
/// Unit suffixes are accepted: 40.5g, 19.05mm, 4cm, 45deg, 250ms.
#[derive(Debug, Parser)]
#[command(name = "thud", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Lift the work caps (Newmark steps, samples, sweep cells, …; `thud limits` lists them).
    #[arg(long, global = true)]
    pub no_limit: bool,
    /// Worker threads for parallel work (sweeps, ensembles, responses, the explorer's chart):
    /// 1 to 1024. Default: RAYON_NUM_THREADS if set, else one per CPU. If the system refuses
    /// some (a pids limit), thud runs with the threads it got and prints one warning.
    #[arg(long, global = true, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<String>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// The pressure pulse of one Hertzian impact at an observer (Eqs 1–24).
    Pulse(Box<pulse::PulseArgs>),
    /// Simulate one impact-damper design through its impacts (Eqs 25–27).
    Simulate(Box<simulate::SimulateArgs>),
    /// Sweep a design over impact mass × gap: the design chart and Table 5.
    Sweep(Box<sweep::SweepArgs>),
    /// The bifurcation diagram of a forced design over any parameter: x(kT), impacts, orbit types.
    Bifurcation(Box<bifurcation::BifurcationArgs>),
    /// The impact map (Poincaré section on impacts) of one forced design.
    ImpactMap(Box<impact_map::ImpactMapArgs>),
    /// The periodic orbit of a forced design, stable or not, by shooting: amplitude, impacts,
    /// Floquet multipliers.
    Orbit(Box<orbit::OrbitArgs>),
    /// Continue a forced design's periodic orbit over one parameter: folds, period doublings,
    /// torus and grazing points, stable and unstable parts.
    Continue(Box<continuation::ContinueArgs>),
    /// The basins of attraction of a forced design over the ball's start (y0 × w0).
    Basins(Box<basins::BasinsArgs>),
    /// The best dampers within your limits: a Pareto front over the variables you give.
    Design(Box<design::DesignSearchArgs>),
    /// Join the parts written by `thud sweep --shard K/N` into the whole chart.
    Merge(Box<merge::MergeArgs>),
    /// The frequency response under a harmonic force: amplitude with and without the damper, Leq.
    Response(Box<response::ResponseArgs>),
    /// Restitution against impact mass (Fig 13), and the c1 that gives a wanted restitution.
    Restitution(Box<restitution::RestitutionArgs>),
    /// Reproduce a table or figure of the paper, beside the paper's numbers.
    Paper(paper::PaperArgs),
    /// Write a design's data (CSV), figures (SVG, PDF) or sound (WAV) to a file.
    Export(Box<export::ExportArgs>),
    /// Calibrate from a measured free decay (CSV): the structure's f_n, ζ, K, C, or a damper's c1.
    Fit(fit::FitArgs),
    /// List the named starting designs (--preset NAME).
    Presets(presets::PresetsArgs),
    /// The interactive explorer (the default with no subcommand).
    Tui(tui::TuiArgs),
    /// The valid range of every parameter and the work cap of every run.
    Limits(LimitsArgs),
    /// Print a shell completion script: bash, zsh, fish, powershell (or elvish).
    Completions(shell::CompletionsArgs),
    /// Print the man page (roff) of thud, or of one command (`thud man pulse`).
    Man(shell::ManArgs),
    /// The settings file (config.toml): `thud config check` lists every problem in it.
    Config(settings::ConfigArgs),
}

/// `--ascii`, one definition for the explorer and every command that writes a figure.
#[derive(Debug, Clone, Copy, Default, Args)]
pub struct AsciiArgs {
    /// Pure ASCII: plain borders, plot glyphs and text (theta, us) for fonts without Braille; in
    /// a figure every label, tick and title (- for the minus sign, ^2, theta, u for micro).
    #[arg(long)]
    pub ascii: bool,
}

impl AsciiArgs {
    /// The SVG document `svg` as written: as it is, or with `--ascii` every character beyond
    /// ASCII spelled as the explorer spells it (`−` → `-`, `²` → `^2`, `θ` → `theta`,
    /// `µ` → `u`, `τ` → `tau`; anything unknown `?`), escaped for XML (`≤` → `&lt;=`).
    /// Outside text and the title an SVG of thud's is ASCII already.
    #[must_use]
    pub fn figure(self, svg: String) -> String {
        if self.ascii {
            crate::ascii::figure(svg)
        } else {
            svg
        }
    }

    /// Text (a report in Markdown) as written: as it is, or with `--ascii` every character
    /// beyond ASCII spelled as the explorer spells it (`θ` → `theta`, `−` → `-`).
    #[must_use]
    pub fn text(self, text: String) -> String {
        if self.ascii && !text.is_ascii() {
            crate::ascii::fold(&text)
        } else {
            text
        }
    }
}

/// Options of `thud limits`.
#[derive(Debug, Clone, Copy, Args)]
pub struct LimitsArgs {
    /// Print one JSON object {ranges, caps}.
    #[arg(long)]
    json: bool,
}

/// How to print a result.
#[derive(Debug, Clone, Copy, Default, Args)]
pub struct OutputArgs {
    /// Print one JSON object.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print CSV.
    #[arg(long)]
    pub csv: bool,
}

impl OutputArgs {
    pub fn format(self) -> OutputFormat {
        if self.json {
            OutputFormat::Json
        } else if self.csv {
            OutputFormat::Csv
        } else {
            OutputFormat::Text
        }
    }
}

/// Parses the optional flag `--{name}` as a quantity of `kind` and checks it against its range;
/// the error names the flag.
pub(crate) fn quantity(name: &str, text: &Option<String>, kind: Kind, range: &Range) -> Result<Option<f64>, ThudError> {
    text.as_deref()
        .map(|t| {
            let flag = format!("--{name}");
            range.check_as(&flag, units::parse(&flag, t, kind)?)
        })
        .transpose()
}

/// Parses the count flag `--{name}` (a whole number, `1e4` allowed) against its range.
pub(crate) fn count(name: &str, text: &str, range: &Range) -> Result<usize, ThudError> {
    range.parse_count(&format!("--{name}"), text)
}

/// Prints one line on stderr, `thud: …` (never panics, even with stderr closed).
pub(crate) fn warn(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "thud: {}", errors::one_line(line));
}

/// The flags engine errors name bare, without dashes: the parameters of the range table, the
/// sweep axes and the preset (the message names the flag).
fn numeric_flags() -> Vec<String> {
    crate::params::listed_ranges()
        .into_iter()
        .map(|r| r.param)
        .chain(["masses", "gaps", "preset", "design", "freqs", "data", "save"])
        .map(str::to_string)
        .collect()
}

/// The command path the user typed up to a command that needs a subcommand, and its
/// subcommands ("thud export", [csv, svg, pdf, wav]).
fn missing_subcommand(args: &[String]) -> Option<(String, Vec<String>)> {
    let mut cmd = Cli::command();
    let mut path = vec!["thud".to_string()];
    for a in args.iter().skip(1).filter(|a| !a.starts_with('-')) {
        match cmd.find_subcommand(a) {
            Some(sub) => {
                path.push(a.clone());
                cmd = sub.clone();
            }
            None => break,
        }
    }
    let subs: Vec<String> =
        cmd.get_subcommands().filter(|s| s.get_name() != "help").map(|s| s.get_name().to_string()).collect();
    (!subs.is_empty()).then(|| (path.join(" "), subs))
}

/// The whole command line: parses the arguments (a clap error becomes one line, exit 2; help
/// and version print and exit 0), runs the command, returns the exit code.
pub fn main() -> i32 {
    // Parsed as the OS gave them: a file name is bytes, not necessarily UTF-8.
    let raw: Vec<std::ffi::OsString> = std::env::args_os().collect();
    let args: Vec<String> = raw.iter().map(|a| a.to_string_lossy().into_owned()).collect();
    match Cli::try_parse_from(&raw) {
        Ok(cli) => run(cli),
        Err(e) => {
            use clap::error::ErrorKind;
            match e.kind() {
                ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => match e.print() {
                    Ok(()) => 0,
                    // A closed pipe (`thud --help | head -1`) ends quietly, as for any output.
                    Err(io) if io.kind() == std::io::ErrorKind::BrokenPipe => 0,
                    Err(io) => {
                        let what = if e.kind() == ErrorKind::DisplayHelp { "help" } else { "version" };
                        warn(&format!("cannot write the {what}: {io}"));
                        1
                    }
                },
                ErrorKind::InvalidUtf8 => {
                    warn(&not_utf8(&raw));
                    2
                }
                _ => {
                    warn(&errors::clap_line(&e, missing_subcommand(&args)));
                    2
                }
            }
        }
    }
}

/// The one line for an argument that is not UTF-8 where text is expected (only file names may
/// be any bytes): the flag before it and the value, escaped.
fn not_utf8(raw: &[std::ffi::OsString]) -> String {
    let at = raw.iter().position(|a| a.to_str().is_none()).unwrap_or(0);
    let value = crate::fsio::shown(std::path::Path::new(&raw[at]));
    match raw[..at].last().and_then(|f| f.to_str()).filter(|f| f.starts_with('-')) {
        Some(flag) => format!("invalid {flag}: '{value}' is not UTF-8 text (only a file name may be any bytes)"),
        None => format!("invalid argument '{value}': not UTF-8 text (only a file name may be any bytes)"),
    }
}

/// The exit code of the explorer: 0, or its error's ([`CliError::report`]: the preset named as
/// the flag `--preset`) with its line on stderr.
fn tui_exit(r: Result<(), CliError>, on_success: impl FnOnce()) -> i32 {
    r.map_or_else(
        |e| {
            let (code, line) = e.report(&numeric_flags());
            if let Some(line) = line {
                warn(&line);
            }
            code
        },
        |()| {
            on_success();
            0
        },
    )
}

/// Runs the CLI on `args`; returns the process exit code. Errors are one line on stderr.
pub fn run(cli: Cli) -> i32 {
    // The explorer's own threads: input, hang-up watch, signals, five job slots, an export.
    let reserve = if matches!(cli.command, Some(Command::Tui(_)) | None) { 9 } else { 1 };
    // The pool's warnings are printed only beside a success, as the config's: a failure is its
    // one error line.
    let thread_warnings = match start_threads(cli.threads.as_deref(), reserve) {
        Ok(w) => w,
        Err(e) => return fail(&e),
    };
    let warn_threads = || thread_warnings.iter().for_each(|w| warn(w));
    settings::load();
    let checking_config = matches!(cli.command, Some(Command::Config(_)));
    let ctx = Ctx { no_limit: cli.no_limit };
    budget::set_no_limit(cli.no_limit);
    let mut out = Out::new();
    let result = match cli.command {
        Some(Command::Pulse(a)) => pulse::run(&a, &ctx, &mut out),
        Some(Command::Simulate(a)) => simulate::run(&a, &ctx, &mut out),
        Some(Command::Sweep(a)) => sweep::run(&a, &ctx, &mut out),
        Some(Command::Bifurcation(a)) => bifurcation::run(&a, &ctx, &mut out),
        Some(Command::ImpactMap(a)) => impact_map::run(&a, &ctx, &mut out),
        Some(Command::Orbit(a)) => orbit::run(&a, &ctx, &mut out),
        Some(Command::Continue(a)) => continuation::run(&a, &ctx, &mut out),
        Some(Command::Basins(a)) => basins::run(&a, &ctx, &mut out),
        Some(Command::Merge(a)) => merge::run(&a, &ctx, &mut out),
        Some(Command::Design(a)) => design::run(&a, &ctx, &mut out),
        Some(Command::Response(a)) => response::run(&a, &ctx, &mut out),
        Some(Command::Restitution(a)) => restitution::run(&a, &ctx, &mut out),
        Some(Command::Paper(a)) => paper::run(&a, &mut out),
        Some(Command::Export(a)) => export::run(&a, &ctx),
        Some(Command::Fit(a)) => fit::run(&a, &ctx, &mut out),
        Some(Command::Presets(a)) => presets::run(&a, &mut out),
        Some(Command::Limits(a)) => limits(&a, &mut out),
        Some(Command::Completions(a)) => shell::completions(&a, &mut out),
        Some(Command::Man(a)) => shell::man(&a, &mut out),
        Some(Command::Config(a)) => settings::run(&a, &mut out),
        Some(Command::Tui(a)) => return tui_exit(tui::run(&a), warn_threads),
        None => return tui_exit(tui::run_default(), warn_threads),
    };
    match result.and_then(|()| out.flush()) {
        Ok(()) => {
            warn_threads();
            // A config warning only beside a success: a failure is its one error line.
            if let Some(w) = settings::warning().filter(|_| !checking_config) {
                warn(w);
            }
            0
        }
        Err(e) => fail(&e),
    }
}

/// Prints `e`'s line (if any) and returns its exit code.
fn fail(e: &CliError) -> i32 {
    let (code, line) = e.report(&numeric_flags());
    if let Some(line) = line {
        warn(&line);
    }
    code
}

/// Builds the parallel pool ([`crate::threads`]) from `--threads` or `RAYON_NUM_THREADS`,
/// leaving room for `reserve` other threads;
/// a pool smaller than wanted is a one-line warning (returned, for the caller to print beside a
/// success), a bad `--threads` an error.
fn start_threads(flag: Option<&str>, reserve: usize) -> Result<Vec<String>, CliError> {
    let flag = flag.map(|t| count("threads", t, &crate::limits::THREADS)).transpose()?;
    let env = std::env::var(crate::threads::ENV).ok();
    let (wanted, too_many) = crate::threads::wanted(flag, env.as_deref());
    let pool = crate::threads::init(wanted, reserve);
    Ok(too_many.into_iter().chain(pool.warning).collect())
}

/// `thud limits`: the table of ranges and caps.
fn limits(a: &LimitsArgs, out: &mut Out) -> Result<(), CliError> {
    use crate::limits::{CAPS, COUNTS};
    let ranges = crate::params::listed_ranges();
    if a.json {
        // The sweep axis's N is a part of FROM:TO:N, not a flag: the text lists it, the JSON
        // the flags.
        let ranges: Vec<serde_json::Value> = ranges
            .into_iter()
            .chain(COUNTS.into_iter().filter(|r| r.param != crate::limits::GRID_N.param))
            .map(|r| {
                serde_json::json!({ "param": r.param, "what": r.what, "min": r.min, "max": r.max,
                    "unit": r.unit, "reason": r.reason })
            })
            .collect();
        let caps: Vec<serde_json::Value> =
            CAPS.iter().map(|c| serde_json::json!({ "what": c.what, "max": c.max, "basis": c.basis })).collect();
        let solver: Vec<serde_json::Value> = crate::damper::SOLVER_CAPS
            .iter()
            .map(|c| serde_json::json!({ "what": c.what, "max": c.max, "basis": c.basis }))
            .collect();
        return out.json(&serde_json::json!({ "ranges": ranges, "caps": caps, "solver_caps": solver,
            "settle_periods_max": crate::damper::SETTLE_PERIODS_MAX,
            "orbit_transient_periods_max": crate::orbit::MAX_TRANSIENT_PERIODS,
            "orbit_seed_impacts_max": crate::orbit::SETTLE_IMPACTS_MAX }));
    }
    let mut s = String::from("Ranges (a plain number is in the unit shown; θ is narrowed by the source type):\n");
    for r in ranges.into_iter().chain(COUNTS) {
        let flag =
            if r.param == "N" { "FROM:TO:N".to_string() } else { format!("--{}", design_args::flag_of(r.param)) };
        s += &format!("  {flag:<17} {:<26} {:<24} {}\n", r.what, r.describe(), r.reason);
    }
    s += "\nWork caps per run (--no-limit lifts them):\n";
    for c in &CAPS {
        s += &format!("  {:<24} {:>8}   {}\n", c.what, crate::limits::short(c.max), c.basis);
    }
    s += "\nSolver caps per run (--no-limit lifts them; a run one stops is reported truncated):\n";
    for c in &crate::damper::SOLVER_CAPS {
        s += &format!("  {:<34} {:>8}   {}\n", c.what, crate::limits::short(c.max), c.basis);
    }
    s += &format!(
        "\nSettling (part of the settling test, not a work cap): a forced run with --settle goes on at most {} periods past its duration; a motion that has not settled by then is reported not settled\n",
        crate::damper::SETTLE_PERIODS_MAX
    );
    s += &format!(
        "Orbits (part of the search, not a work cap): `orbit` and the seeds of `continue --vary NAME=FROM:TO:N` follow the motion at most {} periods (a seed at most {} impacts) before Newton's method takes over; a motion still not repeating is reported as no orbit found\n",
        crate::orbit::MAX_TRANSIENT_PERIODS,
        crate::orbit::SETTLE_IMPACTS_MAX
    );
    out.text(&s)
}
