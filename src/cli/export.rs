//! `thud export csv|svg|wav`: a design's data, figures and sound as files.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::{Args, Subcommand, ValueEnum};

use super::design_args::{parse_range, DesignArgs};
use super::quantity;
use crate::error::ThudError;
use crate::export::{self, wav::WavOptions, ExportError, ExportOptions, Kind};
use crate::fsio::{self, FsError, Overwrite};
use crate::units::Kind as Unit;

#[derive(Debug, Clone, Args)]
pub struct ExportArgs {
    #[command(subcommand)]
    what: ExportCommand,
}

#[derive(Debug, Clone, Subcommand)]
enum ExportCommand {
    /// Data as CSV: waveform (t_s,p_pa), history (t_s,x_m,y_m,x_free_m), impacts, sweep.
    Csv(CsvArgs),
    /// Figures as SVG: waveform, directivity, history, restitution, chart, fig17.
    Svg(SvgArgs),
    /// The damper's sound at the observer: 48 kHz mono 32-bit float, 1.0 = --full-scale Pa.
    Wav(WavArgs),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum CsvWhat {
    Waveform,
    History,
    Impacts,
    Sweep,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum SvgWhat {
    Waveform,
    Directivity,
    History,
    Restitution,
    Chart,
    Fig17,
}

#[derive(Debug, Clone, Args)]
struct CsvArgs {
    #[arg(value_enum)]
    what: CsvWhat,
    #[command(flatten)]
    common: Common,
}

#[derive(Debug, Clone, Args)]
struct SvgArgs {
    #[arg(value_enum)]
    what: SvgWhat,
    #[command(flatten)]
    common: Common,
}

#[derive(Debug, Clone, Args)]
struct WavArgs {
    /// Pressure written as sample value 1.0 (Pa); the same for every design, so files compare by ear.
    #[arg(long, value_name = "PA", default_value = "20")]
    full_scale: String,
    #[command(flatten)]
    common: Common,
}

/// The options every export takes.
#[derive(Debug, Clone, Args)]
struct Common {
    #[command(flatten)]
    design: DesignArgs,
    /// Impact speed U0 of waveform/directivity/restitution (m/s) [default: the design's largest impact speed; 1.4 for restitution].
    #[arg(long, value_name = "U", allow_hyphen_values = true)]
    u0: Option<String>,
    /// Impact masses FROM:TO:N of sweep/chart/fig17 [default: 30g:100g:20] and restitution [default: 5g:100g:20].
    #[arg(long, value_name = "FROM:TO:N")]
    masses: Option<String>,
    /// Gaps FROM:TO:N of sweep/chart/fig17 [default: 2cm:5cm:20].
    #[arg(long, value_name = "FROM:TO:N")]
    gaps: Option<String>,
    /// Points of a waveform or time history.
    #[arg(long, value_name = "N", default_value_t = 2001)]
    points: usize,
    /// The file to write (`-`: standard output). An existing file is kept unless --force.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// Replace the --out file if it exists (atomically; never a device, FIFO or folder).
    #[arg(long)]
    force: bool,
}

impl Common {
    fn options(&self) -> Result<ExportOptions, ThudError> {
        Ok(ExportOptions {
            u0_m_s: quantity("u0", &self.u0, Unit::Speed)?,
            masses_kg: self.masses.as_deref().map(|m| parse_range("masses", m, Unit::Mass)).transpose()?,
            gaps_m: self.gaps.as_deref().map(|g| parse_range("gaps", g, Unit::Length)).transpose()?,
            points: self.points,
            wav: WavOptions::default(),
        })
    }
}

/// Renders and writes one export; says on stderr what was written. The target is checked
/// before the work starts, so a refused --out costs nothing.
fn write(kind: Kind, common: &Common, opts: &ExportOptions) -> Result<(), ThudError> {
    if opts.points < 2 {
        return Err(ThudError::invalid("points", format!("{}; must be at least 2", opts.points)));
    }
    let design = common.design.design()?;
    let overwrite = Overwrite::from_force(common.force);
    let out = &common.out;
    if fsio::is_stdout(out) {
        if kind == Kind::Wav && std::io::stdout().is_terminal() {
            return Err(ThudError::invalid(
                "out",
                "-: a WAV file is binary; redirect standard output to a file or a player",
            ));
        }
        let bytes = export::render(kind, &design, opts).map_err(|e| export_error(out, e))?;
        return fsio::write_stdout(&bytes)
            .map_err(|e| ThudError::invalid("out", format!("cannot write to standard output: {e}")));
    }
    fsio::check_target(out, overwrite).map_err(|e| out_error(out, &e))?;
    let bytes = export::render(kind, &design, opts).map_err(|e| export_error(out, e))?;
    fsio::write(out, &bytes, overwrite).map_err(|e| out_error(out, &e))?;
    eprintln!("thud: wrote {}", out.display());
    Ok(())
}

/// An export failure as the CLI's one-line error.
fn export_error(out: &Path, e: ExportError) -> ThudError {
    match e {
        ExportError::Invalid(t) => t,
        ExportError::File(f) => out_error(out, &f),
        ExportError::Csv(c) => ThudError::invalid("out", format!("cannot write {}: {c}", out.display())),
    }
}

/// A refused or failed write of `out` as the CLI's one-line error (exit 2): what is at the
/// path and what to do.
pub(super) fn out_error(out: &Path, e: &FsError) -> ThudError {
    let message = match e {
        FsError::Exists(p) => format!("{} exists; add --force to replace it", p.display()),
        FsError::NotRegular { path, kind } => {
            format!("{} is {kind}; thud writes only regular files (even with --force)", path.display())
        }
        FsError::TooLarge { .. } | FsError::Io { .. } => format!("cannot write {}: {}", out.display(), e.reason()),
    };
    ThudError::invalid("out", message)
}

pub fn run(a: &ExportArgs) -> Result<(), ThudError> {
    match &a.what {
        ExportCommand::Csv(c) => {
            let kind = match c.what {
                CsvWhat::Waveform => Kind::CsvWaveform,
                CsvWhat::History => Kind::CsvHistory,
                CsvWhat::Impacts => Kind::CsvImpacts,
                CsvWhat::Sweep => Kind::CsvSweep,
            };
            write(kind, &c.common, &c.common.options()?)
        }
        ExportCommand::Svg(s) => {
            let kind = match s.what {
                SvgWhat::Waveform => Kind::SvgWaveform,
                SvgWhat::Directivity => Kind::SvgDirectivity,
                SvgWhat::History => Kind::SvgHistory,
                SvgWhat::Restitution => Kind::SvgRestitution,
                SvgWhat::Chart => Kind::SvgChart,
                SvgWhat::Fig17 => Kind::SvgFig17,
            };
            write(kind, &s.common, &s.common.options()?)
        }
        ExportCommand::Wav(w) => {
            let mut opts = w.common.options()?;
            opts.wav.full_scale_pa = crate::units::parse("full-scale", &w.full_scale, Unit::Number)?;
            opts.wav.validate()?;
            write(Kind::Wav, &w.common, &opts)
        }
    }
}
