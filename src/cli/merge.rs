//! `thud merge PARTS… --out FILE`: the parts written by `thud sweep --shard K/N`, checked and
//! joined into the whole chart, printed as `thud sweep --json` / `--csv` would print it.
//!
//! The order of the checks keeps a merge cheap to refuse: first the first line (header) of
//! every part alone — its ranges, its hash, its K/N —, then the headers together (one study,
//! every K once) and the merged chart against its run cap, and only then the cells, each part
//! read whole only if it is no larger than its header allows.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use clap::Args;

use super::sweep::{render, Charted, Target};
use super::{quantity, CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::error::ThudError;
use crate::fsio::{self, FsError};
use crate::limits::{self, short};
use crate::shard::{self, Format, Header, Part, ShardError};
use crate::units::Kind;

#[derive(Debug, Clone, Args)]
pub struct MergeArgs {
    /// The part files of `thud sweep --shard K/N` (JSON lines or CSV), every K once, any order.
    #[arg(value_name = "PARTS", required = true)]
    parts: Vec<PathBuf>,
    /// The file to write (`-`: standard output). An existing file is kept unless --force.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// Replace the --out file if it exists (atomically; only a regular file is ever replaced).
    #[arg(long)]
    force: bool,
    /// Width of the inclination bands of the Table 5 summary (cm/s) [default: the parts' band].
    #[arg(long, value_name = "CM_S", allow_hyphen_values = true)]
    band: Option<String>,
    /// --json or --csv: the chart as `thud sweep` prints it [default: CSV if every part is CSV,
    /// else JSON].
    #[command(flatten)]
    output: OutputArgs,
}

/// A refusal of the parts as the CLI's one-line error (exit 2).
fn refused(e: &ShardError) -> CliError {
    CliError::Refused(format!("merge: {e}"))
}

/// A part that cannot be read, naming it (exit 2).
fn unreadable(name: &str, e: &FsError) -> CliError {
    CliError::Input(ThudError::invalid("PARTS", format!("cannot read {name}: {}", e.reason())))
}

/// Reads the first line of the part at `path` (at most [`shard::MAX_HEADER_BYTES`]) and checks
/// it on its own; no cell is read.
fn read_header(path: &Path, name: &str) -> Result<(Format, Header), CliError> {
    let file = fsio::open_regular(path, shard::MAX_PART_BYTES).map_err(|e| unreadable(name, &e))?;
    let mut line = Vec::new();
    let limit = shard::MAX_HEADER_BYTES as u64 + 1;
    BufReader::new(file)
        .take(limit)
        .read_until(b'\n', &mut line)
        .map_err(|e| unreadable(name, &FsError::Io { path: path.to_path_buf(), source: e }))?;
    let not_a_part = |why: &str| refused(&ShardError::NotAPart { file: name.to_string(), why: why.to_string() });
    if line.len() as u64 >= limit {
        return Err(not_a_part("its first line is longer than any shard header"));
    }
    let text = std::str::from_utf8(&line).map_err(|_| not_a_part("its first line is not UTF-8 text"))?;
    shard::parse_header(name, text.trim_end_matches(['\n', '\r'])).map_err(|e| refused(&e))
}

/// Reads the whole part at `path`, at most the size its `header` allows, and checks its cells.
fn read_part(path: &Path, name: &str, header: &Header) -> Result<Part, CliError> {
    let text = fsio::read_to_string(path, header.max_part_bytes()).map_err(|e| match e {
        FsError::TooLarge { limit_bytes, .. } => refused(&ShardError::Invalid {
            file: name.to_string(),
            why: format!(
                "is larger than the {limit_bytes} bytes a part of {} cells × {} runs can take",
                header.end_cell - header.first_cell,
                header.study.ensemble
            ),
        }),
        e => unreadable(name, &e),
    })?;
    let part = shard::parse(name, &text).map_err(|e| refused(&e))?;
    if part.header != *header {
        return Err(refused(&ShardError::Invalid {
            file: name.to_string(),
            why: "changed while it was being merged".into(),
        }));
    }
    Ok(part)
}

/// The parts read whole when the first is a part of a study over any parameter
/// (`sweep --vary … --shard K/N`) or of a bifurcation (`bifurcation --shard K/N`); None for
/// the parts of a mass × gap chart.
fn study_parts(a: &MergeArgs, names: &[String]) -> Result<Option<Vec<(String, String)>>, CliError> {
    let Some(first) = a.parts.first() else { return Ok(None) };
    let text = fsio::read_to_string(first, shard::MAX_PART_BYTES).map_err(|e| unreadable(&names[0], &e))?;
    let first_line = text.lines().next().unwrap_or("");
    if !super::study::is_study_part(first_line) && !super::bifurcation::is_part(first_line) {
        return Ok(None);
    }
    let mut parts = vec![(names[0].clone(), text)];
    for (p, name) in a.parts.iter().zip(names).skip(1) {
        parts.push((name.clone(), fsio::read_to_string(p, shard::MAX_PART_BYTES).map_err(|e| unreadable(name, &e))?));
    }
    Ok(Some(parts))
}

pub fn run(a: &MergeArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let target = Target::new(Some(a.out.as_path()), a.force)?;
    let band = quantity("band", &a.band, Kind::Inclination, &limits::BAND)?;
    let names: Vec<String> = a.parts.iter().map(|p| fsio::shown(p)).collect();
    if let Some(text) = study_parts(a, &names)? {
        if text.first().is_some_and(|(_, t)| super::bifurcation::is_part(t.lines().next().unwrap_or(""))) {
            let format = if a.output.csv { OutputFormat::Csv } else { OutputFormat::Json };
            return target.write(&super::bifurcation::merge(&text, format)?, out);
        }
        let (d, study) = super::study::merge(&text)?;
        let format = if a.output.csv { OutputFormat::Csv } else { OutputFormat::Json };
        return target.write(&super::study::render(&d, &study, format)?, out);
    }
    let headers = a.parts.iter().zip(&names).map(|(p, n)| read_header(p, n)).collect::<Result<Vec<_>, _>>()?;
    shard::check_set(names.iter().map(String::as_str).zip(headers.iter().map(|(_, h)| h))).map_err(|e| refused(&e))?;
    let s = &headers[0].1.study;
    let runs = limits::merged_runs(s.cells(), s.ensemble);
    ctx.enforce(
        runs,
        "PARTS",
        &format!("{} cells × {} runs", s.cells(), s.ensemble),
        &format!("merge a chart of at most {} runs", short(runs.cap.max)),
    )?;
    let mut parts = Vec::with_capacity(headers.len());
    for ((path, name), (_, header)) in a.parts.iter().zip(&names).zip(&headers) {
        parts.push((name.clone(), read_part(path, name, header)?));
    }
    let merged = shard::merge(parts).map_err(|e| refused(&e))?;
    let s = merged.study.clone();
    let format = match a.output.format() {
        OutputFormat::Text if merged.all_csv => OutputFormat::Csv,
        OutputFormat::Text => OutputFormat::Json,
        f => f,
    };
    let charted =
        if s.ensemble == 1 { Charted::Plain(merged.chart()) } else { Charted::Ensemble(merged.into_ensemble_chart()) };
    let (band, band_text) = match (band, &a.band) {
        (Some(b), Some(typed)) => (b, typed.clone()),
        _ => (s.band_cm_s, format!("{} (the parts' band)", short(s.band_cm_s))),
    };
    let text = render(ctx, &s.design, &charted, band, &band_text, format)?;
    target.write(&text, out)
}
