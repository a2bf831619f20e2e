//! `thud export csv|svg|wav`: a design's data, figures and sound as files.

use std::path::PathBuf;

use clap::{Args, Subcommand, ValueEnum};

use super::design_args::{parse_range, DesignArgs};
use super::quantity;
use crate::error::ThudError;
use crate::export::{self, wav::WavOptions, ExportOptions, Kind};
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
    /// The file to write.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
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

/// Renders and writes one export; says on stderr what was written.
fn write(kind: Kind, common: &Common, opts: &ExportOptions) -> Result<(), ThudError> {
    if opts.points < 2 {
        return Err(ThudError::invalid("points", format!("{}; must be at least 2", opts.points)));
    }
    let design = common.design.design()?;
    export::export_to_path(kind, &design, opts, &common.out)?;
    eprintln!("thud: wrote {}", common.out.display());
    Ok(())
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
