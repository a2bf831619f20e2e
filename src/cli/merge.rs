//! `thud merge PARTS… --out FILE`: the parts written by `thud sweep --shard K/N`, checked and
//! joined into the whole chart, printed as `thud sweep --json` / `--csv` would print it.

use std::path::{Path, PathBuf};

use clap::Args;

use super::sweep::{render, Charted, Target};
use super::{CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::error::ThudError;
use crate::fsio;
use crate::limits::{self, short};
use crate::shard::{self, Part, ShardError};

#[derive(Debug, Clone, Args)]
pub struct MergeArgs {
    /// The part files of `thud sweep --shard K/N` (JSON lines or CSV), every K once, any order.
    #[arg(value_name = "PARTS", required = true)]
    parts: Vec<PathBuf>,
    /// The file to write (`-`: standard output). An existing file is kept unless --force.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// Replace the --out file if it exists (atomically; never a device, FIFO or folder).
    #[arg(long)]
    force: bool,
    /// --json or --csv: the chart as `thud sweep` prints it [default: CSV if every part is CSV,
    /// else JSON].
    #[command(flatten)]
    output: OutputArgs,
}

/// A refusal of the parts as the CLI's one-line error (exit 2).
fn refused(e: &ShardError) -> CliError {
    CliError::Refused(format!("merge: {e}"))
}

/// Reads one part file, bounded, and checks it on its own.
fn read_part(path: &Path) -> Result<(String, Part), CliError> {
    let name = path.display().to_string();
    let text = fsio::read_to_string(path, shard::MAX_PART_BYTES)
        .map_err(|e| CliError::Input(ThudError::invalid("PARTS", format!("cannot read {name}: {}", e.reason()))))?;
    let part = shard::parse(&name, &text).map_err(|e| refused(&e))?;
    Ok((name, part))
}

pub fn run(a: &MergeArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let target = Target::new(Some(a.out.as_path()), a.force)?;
    let parts = a.parts.iter().map(|p| read_part(p)).collect::<Result<Vec<_>, _>>()?;
    let merged = shard::merge(parts).map_err(|e| refused(&e))?;
    let s = merged.study.clone();
    let runs = limits::merged_runs(s.cells(), s.ensemble);
    ctx.enforce(
        runs,
        "PARTS",
        &format!("{} cells × {} runs", s.cells(), s.ensemble),
        &format!("merge a chart of at most {} runs", short(runs.cap.max)),
    )?;
    let format = match a.output.format() {
        OutputFormat::Text if merged.all_csv => OutputFormat::Csv,
        OutputFormat::Text => OutputFormat::Json,
        f => f,
    };
    let charted =
        if s.ensemble == 1 { Charted::Plain(merged.chart()) } else { Charted::Ensemble(merged.into_ensemble_chart()) };
    let text =
        render(ctx, &s.design, &charted, s.band_cm_s, &format!("{} (the parts' band)", short(s.band_cm_s)), format)?;
    target.write(&text, out)
}
