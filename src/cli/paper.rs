//! `thud paper`: the paper's tables and figures, reproduced.

use std::path::{Path, PathBuf};

use clap::Args;

use super::export::write_error;
use super::sweep::Target;
use super::{budget, CliError, Out, OutputArgs, OutputFormat};
use crate::error::ThudError;
use crate::export::report::{self, BundleError};
use crate::fsio::{self, Overwrite};
use crate::paper;

#[derive(Debug, Clone, Args)]
pub struct PaperArgs {
    /// Which table or figure (see --list), or `all` with --out DIR for every one as CSV/SVG (and PDF with --with-pdf) plus REPORT.md.
    #[arg(value_name = "ID", required_unless_present = "list")]
    id: Option<String>,
    /// List every table and figure that can be reproduced.
    #[arg(long)]
    list: bool,
    /// With `all`: the folder for the whole set, written complete or not at all (a new or empty
    /// folder, or with --force one holding a previous set). With one ID: the file for its table
    /// (`-`: standard output), kept if it exists unless --force.
    #[arg(long, value_name = "DIR|FILE")]
    out: Option<PathBuf>,
    /// Replace the previous set in --out (all) or the --out file (one ID), atomically; only
    /// regular files are ever replaced.
    #[arg(long, requires = "out")]
    force: bool,
    /// With `all`: each figure also as ID.pdf beside its ID.svg (text in an embedded DejaVu Sans).
    #[arg(long)]
    with_pdf: bool,
    /// `--pdf`, this switch's name before: `--pdf FILE` names a figure's PDF file elsewhere, so
    /// here it is refused with a line naming `--with-pdf` (hidden from help).
    #[arg(long = "pdf", hide = true, num_args = 0..=1, value_name = "FILE")]
    #[allow(clippy::option_option)]
    old_pdf: Option<Option<PathBuf>>,
    #[command(flatten)]
    ascii: super::AsciiArgs,
    #[command(flatten)]
    output: OutputArgs,
}

pub fn run(a: &PaperArgs, out: &mut Out) -> Result<(), CliError> {
    if a.list {
        let mut s = String::new();
        for item in paper::items() {
            s += &format!("{:<8} {}\n", item.id, item.description);
        }
        return out.text(&s);
    }
    if a.old_pdf.is_some() {
        return Err(ThudError::invalid(
            "--pdf",
            "`thud paper all` writes each figure's PDF with --with-pdf (--pdf FILE names one figure's PDF on bifurcation, impact-map and basins)",
        )
        .into());
    }
    let id = a.id.as_deref().unwrap_or_default().to_ascii_lowercase();
    if id == "all" {
        return all(a.out.as_deref(), Overwrite::from_force(a.force), a.with_pdf, a.ascii);
    }
    if a.ascii.ascii {
        return Err(ThudError::invalid(
            "--ascii",
            format!("the figures are written by `thud paper all --ascii --out DIR`; '{id}' prints a table"),
        )
        .into());
    }
    if a.with_pdf {
        return Err(ThudError::invalid(
            "--with-pdf",
            format!("PDF figures are made by `thud paper all --with-pdf --out DIR`, not for '{id}'"),
        )
        .into());
    }
    let target = Target::new(a.out.as_deref(), a.force)?;
    let table = paper::get(&id).ok_or_else(|| {
        let ids: Vec<&str> = paper::items().map(|i| i.id).collect();
        ThudError::invalid("paper item", format!("unknown '{id}'; one of: {}", ids.join(", ")))
    })??;
    if a.out.is_none() {
        return out.table(&table, a.output.format());
    }
    super::output::check_table(&table)?;
    let mut bytes = Vec::new();
    match a.output.format() {
        OutputFormat::Text => super::format::write_text(&mut bytes, &table)?,
        OutputFormat::Csv => super::format::write_csv(&mut bytes, &table)?,
        OutputFormat::Json => {
            serde_json::to_writer_pretty(&mut bytes, &super::format::table_json(&table))
                .map_err(std::io::Error::from)?;
            bytes.push(b'\n');
        }
    }
    target.write(&String::from_utf8_lossy(&bytes), out)
}

/// A refusal of `paper all`'s folder `dir` as the CLI's one-line error naming `--out` (exit 2),
/// or a failure of the write itself (a read-only or full disk: exit 1, as for every writer).
fn bundle_error(dir: &Path, e: BundleError) -> CliError {
    match e {
        BundleError::File(f) => write_error(dir, &f),
        e @ BundleError::Pdf { .. } => CliError::Io(e.to_string()),
        e => ThudError::invalid("--out", e.to_string()).into(),
    }
}

/// `thud paper all --out DIR`: every item as CSV (and SVG where plotted; with `pdf` PDF too) plus REPORT.md, as one
/// folder written complete or not at all ([`report::write_bundle`]). The folder is checked
/// before the work starts, and every number in every file before the first file is written.
/// With `ascii` (`--ascii`) every figure's text is spelled in ASCII, in its SVG and its PDF,
/// and so is REPORT.md.
fn all(out: Option<&Path>, overwrite: Overwrite, pdf: bool, ascii: super::AsciiArgs) -> Result<(), CliError> {
    let dir = out.ok_or_else(|| ThudError::invalid("--out", "`thud paper all` needs --out DIR"))?;
    if fsio::is_stdout(dir) {
        return Err(ThudError::invalid("--out", "-: `thud paper all` writes a folder of files; give --out DIR").into());
    }
    let expected = report::expected_files_with(true);
    report::check_bundle_targets(dir, expected.iter().map(String::as_str), overwrite)
        .map_err(|e| bundle_error(dir, e))?;
    let spinner = budget::spinner("reproducing the paper", true);
    let mut files = report::paper_bundle();
    spinner.finish_and_clear();
    for f in &mut files {
        match Path::new(&f.name).extension().and_then(|e| e.to_str()) {
            Some("svg") => f.contents = ascii.figure(std::mem::take(&mut f.contents)),
            Some("md") => f.contents = ascii.text(std::mem::take(&mut f.contents)),
            _ => {}
        }
    }
    for f in &files {
        super::output::check_text(&f.contents).map_err(|e| {
            if let CliError::NonFinite(w) = e {
                CliError::NonFinite(format!("{w} in {}", f.name))
            } else {
                e
            }
        })?;
    }
    let pdfs = if pdf { report::pdf_files(&files).map_err(|e| bundle_error(dir, e))? } else { Vec::new() };
    let all: Vec<(&str, &[u8])> = files
        .iter()
        .map(|f| (f.name.as_str(), f.contents.as_bytes()))
        .chain(pdfs.iter().map(|(name, bytes)| (name.as_str(), bytes.as_slice())))
        .collect();
    report::write_bundle(dir, &all, overwrite).map_err(|e| bundle_error(dir, e))?;
    super::warn(&format!("wrote {} files to {}", all.len(), fsio::shown(dir)));
    Ok(())
}
