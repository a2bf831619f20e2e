//! The command-line front end: parses arguments (units at the edge), calls the engine and
//! prints text, JSON or CSV. No physics here.

pub mod design_args;
mod export;
mod format;
mod paper;
mod presets;
mod pulse;
mod restitution;
mod settings;
mod simulate;
mod sweep;
mod tui;

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::acoustics::{PulseShape, QuadSigns, Source};
use crate::error::ThudError;
use crate::units::{self, Kind};

pub use format::{print_table, OutputFormat};

/// thud — design single-unit impact dampers: Hertz contact, impact noise and a live explorer.
///
/// Plain numbers are SI units (kg, m, m/s, N/m^1.5, Pa·s/m) except angles, which are degrees.
/// Unit suffixes are accepted: 40.5g, 19.05mm, 4cm, 45deg, 250ms.
#[derive(Debug, Parser)]
#[command(name = "thud", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// The pressure pulse of one Hertzian impact at an observer (Eqs 1–24).
    Pulse(Box<pulse::PulseArgs>),
    /// Simulate one impact-damper design through its impacts (Eqs 25–27).
    Simulate(Box<simulate::SimulateArgs>),
    /// Sweep a design over impact mass × gap: the design chart and Table 5.
    Sweep(Box<sweep::SweepArgs>),
    /// Restitution against impact mass (Fig 13), and the c1 that gives a wanted restitution.
    Restitution(Box<restitution::RestitutionArgs>),
    /// Reproduce a table or figure of the paper, beside the paper's numbers.
    Paper(paper::PaperArgs),
    /// Write a design's data (CSV), figures (SVG) or sound (WAV) to a file.
    Export(Box<export::ExportArgs>),
    /// List the named starting designs (--preset NAME).
    Presets(presets::PresetsArgs),
    /// The interactive explorer (the default with no subcommand).
    Tui(tui::TuiArgs),
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

/// Source type on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SourceArg {
    Single,
    Dipole,
    Quadrupole,
}

impl From<SourceArg> for Source {
    fn from(s: SourceArg) -> Self {
        match s {
            SourceArg::Single => Source::Single,
            SourceArg::Dipole => Source::Dipole,
            SourceArg::Quadrupole => Source::Quadrupole,
        }
    }
}

/// Acceleration pulse shape on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PulseArg {
    /// The paper's half-sine, Eq 7.
    HalfSine,
    /// The exact Hertz pulse.
    Hertz,
}

impl From<PulseArg> for PulseShape {
    fn from(p: PulseArg) -> Self {
        match p {
            PulseArg::HalfSine => PulseShape::HalfSine,
            PulseArg::Hertz => PulseShape::Hertz,
        }
    }
}

/// Quadrupole image signs on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum QuadSignsArg {
    Paper,
    Rigid,
}

impl From<QuadSignsArg> for QuadSigns {
    fn from(s: QuadSignsArg) -> Self {
        match s {
            QuadSignsArg::Paper => QuadSigns::Paper,
            QuadSignsArg::Rigid => QuadSigns::Rigid,
        }
    }
}

/// Parses an optional quantity flag.
pub(crate) fn quantity(param: &str, text: &Option<String>, kind: Kind) -> Result<Option<f64>, ThudError> {
    text.as_deref().map(|t| units::parse(param, t, kind)).transpose()
}

/// The exit code of the explorer: 0, or 2 with the error on stderr.
fn tui_exit(r: Result<(), String>) -> i32 {
    r.map_or_else(
        |e| {
            eprintln!("thud: {e}");
            2
        },
        |()| 0,
    )
}

/// Runs the CLI on `args`; returns the process exit code. Errors are one line on stderr.
pub fn run(cli: Cli) -> i32 {
    settings::load();
    let result = match cli.command {
        Some(Command::Pulse(a)) => pulse::run(&a),
        Some(Command::Simulate(a)) => simulate::run(&a),
        Some(Command::Sweep(a)) => sweep::run(&a),
        Some(Command::Restitution(a)) => restitution::run(&a),
        Some(Command::Paper(a)) => paper::run(&a),
        Some(Command::Export(a)) => export::run(&a),
        Some(Command::Presets(a)) => presets::run(&a),
        Some(Command::Tui(a)) => return tui_exit(tui::run(&a)),
        None => return tui_exit(tui::run_default()),
    };
    match result {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("thud: {e}");
            2
        }
    }
}
