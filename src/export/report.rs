//! `paper all`: every reproducible table and figure as CSV (and SVG where it is a figure or a
//! table worth plotting), and a `REPORT.md` with the side-by-side tables, notes and errors.

use std::path::Path;

use crate::design::Thresholds;
use crate::fsio::{self, FsError, Overwrite};
use crate::paper::{self, Table, Value};
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
fn md_cell(v: &Value) -> String {
    match v {
        Value::Num(x) => num(*x),
        Value::Text(s) => s.replace('|', "\\|"),
        Value::Missing => "—".into(),
    }
}

/// `table` as a markdown table (or, past [`REPORT_ROWS`] rows, a pointer to its CSV), followed
/// by its notes.
pub fn markdown(table: &Table) -> String {
    let labels: Vec<String> = table.columns.iter().map(|c| c.label.replace('|', "\\|")).collect();
    let mut s = String::new();
    if table.rows.len() <= REPORT_ROWS {
        s += &format!("| {} |\n|{}\n", labels.join(" | "), "---:|".repeat(labels.len()));
        for row in &table.rows {
            s += &format!("| {} |\n", row.iter().map(md_cell).collect::<Vec<_>>().join(" | "));
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

/// Checks that every file of `names` may be written into `dir` with `overwrite` (see
/// [`fsio::check_target`]); the first that may not is the error. Run before the bundle is
/// computed, so a refusal costs nothing.
pub fn check_bundle_targets<'a>(
    dir: &Path,
    names: impl IntoIterator<Item = &'a str>,
    overwrite: Overwrite,
) -> Result<(), FsError> {
    for name in names {
        fsio::check_target(&dir.join(name), overwrite)?;
    }
    Ok(())
}

/// Writes `files` into `dir` (created if missing), each through [`fsio::write`]. Every target is
/// checked first, so a refusal (an existing file without `Replace`, or a path that is not a
/// regular file) writes nothing.
pub fn write_bundle(dir: &Path, files: &[BundleFile], overwrite: Overwrite) -> Result<(), FsError> {
    check_bundle_targets(dir, files.iter().map(|f| f.name.as_str()), overwrite)?;
    for f in files {
        fsio::write(&dir.join(&f.name), f.contents.as_bytes(), overwrite)?;
    }
    Ok(())
}
