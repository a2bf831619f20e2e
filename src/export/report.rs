//! `paper all`: every reproducible table and figure as CSV (and SVG where it is a figure or a
//! table worth plotting), and a `REPORT.md` with the side-by-side tables, notes and errors;
//! with `--pdf` each SVG also as `ID.pdf` ([`pdf_files`]).

use std::fs;
use std::path::{Path, PathBuf};

use crate::design::Thresholds;
use crate::fsio::{self, FsError, Overwrite};
use crate::paper::{self, Column, Table, Value};
use crate::presets;
use crate::units::num;

use super::{csv, figures};

/// Tables with at most this many rows are printed in the report; longer ones (waveforms,
/// histories, chart grids) are only pointed to (their CSV and figure).
pub const REPORT_ROWS: usize = 60;

/// One file of the bundle: a name inside the output folder and its contents.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BundleFile {
    pub name: String,
    pub contents: String,
}

/// A cell of a markdown table ('|' escaped).
fn md_cell(v: &Value, c: &Column) -> String {
    c.text(v, num).replace('|', "\\|")
}

/// `table` as a markdown table (or, past [`REPORT_ROWS`] rows, a pointer to its CSV), followed
/// by its notes.
pub fn markdown(table: &Table) -> String {
    let labels: Vec<String> = table.columns.iter().map(|c| c.label.replace('|', "\\|")).collect();
    let mut s = String::new();
    if table.rows.len() <= REPORT_ROWS {
        s += &format!("| {} |\n|{}\n", labels.join(" | "), "---:|".repeat(labels.len()));
        for row in table.rows.iter().chain(&table.summary) {
            s += &format!(
                "| {} |\n",
                row.iter().zip(&table.columns).map(|(v, c)| md_cell(v, c)).collect::<Vec<_>>().join(" | ")
            );
        }
    } else {
        s += &format!("*{} rows of {} — in `{}.csv`.*\n", table.rows.len(), labels.join(", "), table.id);
    }
    if !table.notes.is_empty() {
        s += "\n";
        for n in &table.notes {
            s += &format!("- {n}\n");
        }
    }
    s
}

/// The thresholds of the paper's design charts (those of preset paper-table3).
fn chart_thresholds() -> Thresholds {
    presets::preset("paper-table3").map(|d| d.thresholds).unwrap_or_default()
}

/// Every item of [`paper::items`] computed: `{id}.csv` and `{id}.svg` (where plotted) per
/// item, and `REPORT.md` last. An item that fails is reported in `REPORT.md` with its error.
pub fn paper_bundle() -> Vec<BundleFile> {
    let thresholds = chart_thresholds();
    let mut files = Vec::new();
    let mut report = String::from(
        "# thud — the paper's tables and figures, reproduced\n\nEach item: the model beside the paper's printed numbers where the paper prints any, the conventions used and the deviations found. Files: `ID.csv` for every item, `ID.svg` for figures and tables worth plotting.\n\n",
    );
    for item in paper::items() {
        report += &format!("## {} — {}\n\n", item.id, item.description);
        match paper::get(item.id) {
            Some(Ok(table)) => {
                let contents = match csv::table(&table) {
                    Ok(text) => text,
                    Err(e) => {
                        report += &format!("**Error:** {e}\n\n");
                        continue;
                    }
                };
                let mut names = vec![format!("{}.csv", item.id)];
                files.push(BundleFile { name: names[0].clone(), contents });
                if let Some(svg) = figures::paper_figure(&table, &thresholds, &super::svg::Look::default()) {
                    names.push(format!("{}.svg", item.id));
                    files.push(BundleFile { name: names[1].clone(), contents: svg });
                }
                let links: Vec<String> = names.iter().map(|n| format!("[`{n}`]({n})")).collect();
                report += &format!("**{}**  \nFiles: {}\n\n", table.title, links.join(", "));
                if names.len() > 1 {
                    report += &format!("![{}]({})\n\n", item.id, names[1]);
                }
                report += &markdown(&table);
            }
            Some(Err(e)) => report += &format!("**Error:** {e}\n"),
            None => report += "**Error:** no such item\n",
        }
        report += "\n";
    }
    files.push(BundleFile { name: "REPORT.md".into(), contents: report });
    files
}

/// The names of the files [`paper_bundle`] produces when every item succeeds.
pub fn expected_files() -> Vec<String> {
    let mut v: Vec<String> = Vec::new();
    for item in paper::items() {
        v.push(format!("{}.csv", item.id));
        if figures::has_figure(item.id) {
            v.push(format!("{}.svg", item.id));
        }
    }
    v.push("REPORT.md".into());
    v
}

/// The names of the files [`paper_bundle`] produces, and with `pdf` the PDF of each figure
/// ([`pdf_files`]) after them.
pub fn expected_files_with(pdf: bool) -> Vec<String> {
    let mut v = expected_files();
    if pdf {
        v.extend(v.iter().filter_map(|n| n.strip_suffix(".svg")).map(|id| format!("{id}.pdf")).collect::<Vec<_>>());
    }
    v
}

/// The file `ID.pdf` of a set's `ID.svg`.
pub fn pdf_name(svg_name: &str) -> Option<String> {
    svg_name.strip_suffix(".svg").map(|id| format!("{id}.pdf"))
}

/// Each SVG figure of `files` as a PDF ([`super::pdf::from_svg`]), named by [`pdf_name`].
pub fn pdf_files(files: &[BundleFile]) -> Result<Vec<(String, Vec<u8>)>, BundleError> {
    files
        .iter()
        .filter_map(|f| Some((pdf_name(&f.name)?, f)))
        .map(|(name, f)| match super::pdf::from_svg(&f.contents) {
            Ok(bytes) => Ok((name, bytes)),
            Err(source) => Err(BundleError::Pdf { name: f.name.clone(), source }),
        })
        .collect()
}

/// Why `paper all` may not write its set into a folder.
#[derive(Debug, thiserror::Error)]
pub enum BundleError {
    /// A file of the set (or the folder) is in the way, or the system refused.
    #[error(transparent)]
    File(#[from] FsError),
    /// The folder holds a file that is not one of the set: the set would be mixed with it.
    #[error(
        "{} holds {} that `thud paper all` does not write; give a new or empty folder (or, with --force, one holding only a previous set)",
        fsio::shown(.dir),
        fsio::shown(.name)
    )]
    Foreign { dir: PathBuf, name: PathBuf },
    /// The path is not a folder.
    #[error("{} is {what}, not a folder", fsio::shown(.dir))]
    NotAFolder { dir: PathBuf, what: String },
    /// A figure could not be made a PDF (a bug: a glyph missing from the embedded font).
    #[error("cannot make {name} a PDF: {source}")]
    Pdf { name: String, source: super::pdf::PdfError },
}

/// What writing the set into a folder does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BundlePlan {
    /// Nothing is there (or an empty folder): the new folder is renamed into place.
    Create,
    /// A previous set is there (`Replace`): the new folder is exchanged with it.
    Replace,
}

/// Checks that the set of `names` may be written as the folder `dir` with `overwrite`: `dir`
/// absent, an empty folder, or (with `Replace`) a folder holding only regular files of the set.
/// Run before the bundle is computed, so a refusal costs nothing.
pub fn check_bundle_targets<'a>(
    dir: &Path,
    names: impl IntoIterator<Item = &'a str>,
    overwrite: Overwrite,
) -> Result<BundlePlan, BundleError> {
    let meta = match fs::symlink_metadata(dir) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(BundlePlan::Create),
        Err(e) => return Err(FsError::Io { path: dir.to_path_buf(), source: e }.into()),
    };
    if !meta.is_dir() {
        let what = if meta.file_type().is_symlink() { "a symbolic link".into() } else { kind_of(&meta) };
        return Err(BundleError::NotAFolder { dir: dir.to_path_buf(), what });
    }
    let names: Vec<&str> = names.into_iter().collect();
    let mut present: Vec<PathBuf> = Vec::new();
    for entry in fs::read_dir(dir).map_err(|e| FsError::Io { path: dir.to_path_buf(), source: e })? {
        let entry = entry.map_err(|e| FsError::Io { path: dir.to_path_buf(), source: e })?;
        let name = entry.file_name();
        if !names.iter().any(|n| name == std::ffi::OsStr::new(n)) {
            return Err(BundleError::Foreign { dir: dir.to_path_buf(), name: name.into() });
        }
        present.push(entry.path());
    }
    present.sort();
    for p in &present {
        if let fsio::Plan::Through(_) = fsio::check_target(p, Overwrite::Replace)? {
            // A stream among the set's names is never replaced either.
            return Err(FsError::Link(p.clone()).into());
        }
    }
    match (present.first(), overwrite) {
        (None, _) => Ok(BundlePlan::Create),
        (Some(p), Overwrite::Refuse) => Err(FsError::Exists(p.clone()).into()),
        (Some(_), Overwrite::Replace) => Ok(BundlePlan::Replace),
    }
}

/// "a regular file", "a FIFO", … for a message.
fn kind_of(meta: &fs::Metadata) -> String {
    fsio::FileKind::of(meta.file_type()).map_or_else(|| "a regular file".into(), |k| k.to_string())
}

/// Writes `files` (name, contents) as the folder `dir`, complete or not at all: into a new temporary folder
/// `.DIR.thud-XXXXXX.tmp` beside it (locked, removed on every error and on every signal of
/// [`crate::signals::handled`]; after SIGKILL, by the next run), each file through
/// [`fsio::TempFolder::write`] and synced, then
/// renamed into place — over nothing, over an empty folder, or (`Replace`) exchanged atomically
/// with the previous set, which is then removed. A full disk or a kill leaves no partial set
/// (nor a folder created above it), and a run after a failure starts afresh. A previous set may hold the PDFs of the set's
/// figures ([`pdf_name`]) whether or not this one does.
pub fn write_bundle(dir: &Path, files: &[(&str, &[u8])], overwrite: Overwrite) -> Result<(), BundleError> {
    let twins: Vec<String> = files.iter().filter_map(|(name, _)| pdf_name(name)).collect();
    let mut names: Vec<&str> = files.iter().map(|(name, _)| *name).collect();
    names.extend(twins.iter().map(String::as_str).filter(|t| !names.contains(t)).collect::<Vec<_>>());
    let plan = check_bundle_targets(dir, names.iter().copied(), overwrite)?;
    let io = |e: std::io::Error| BundleError::from(FsError::Io { path: dir.to_path_buf(), source: e });
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let new_folders = fsio::NewFolders::create(&parent).map_err(io)?;
    fsio::remove_stale_temps(&parent);
    let temp = fsio::TempFolder::new(&parent, dir).map_err(io)?;
    for (name, contents) in files {
        temp.write(name, contents)?;
    }
    temp.sync();
    temp.put_in_place(dir, plan == BundlePlan::Replace, &names)?;
    new_folders.keep();
    Ok(())
}
