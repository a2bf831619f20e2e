//! `thud paper`: the paper's tables and figures, reproduced.

use std::path::PathBuf;

use clap::Args;

use super::{budget, CliError, Out, OutputArgs};
use crate::error::ThudError;
use crate::paper;

#[derive(Debug, Clone, Args)]
pub struct PaperArgs {
    /// Which table or figure (see --list), or `all` with --out DIR for every one as CSV/SVG plus REPORT.md.
    #[arg(value_name = "ID", required_unless_present = "list")]
    id: Option<String>,
    /// List every table and figure that can be reproduced.
    #[arg(long)]
    list: bool,
    /// Folder for `thud paper all` (created if missing).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
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
    let id = a.id.as_deref().unwrap_or_default().to_ascii_lowercase();
    if id == "all" {
        return all(a.out.as_deref());
    }
    let table = paper::get(&id).ok_or_else(|| {
        let ids: Vec<&str> = paper::items().map(|i| i.id).collect();
        ThudError::invalid("paper item", format!("unknown '{id}'; one of: {}", ids.join(", ")))
    })??;
    out.table(&table, a.output.format())
}

/// `thud paper all --out DIR`: every item as CSV (and SVG where plotted) plus REPORT.md.
fn all(out: Option<&std::path::Path>) -> Result<(), CliError> {
    let dir = out.ok_or_else(|| ThudError::invalid("out", "`thud paper all` needs --out DIR"))?;
    let spinner = budget::spinner("reproducing the paper", true);
    let files = crate::export::report::paper_bundle();
    spinner.finish_and_clear();
    // Every number in every file is checked before the first file is written.
    for f in &files {
        super::output::check_text(&f.contents).map_err(|e| {
            if let CliError::NonFinite(w) = e {
                CliError::NonFinite(format!("{w} in {}", f.name))
            } else {
                e
            }
        })?;
    }
    for f in &files {
        crate::export::write_file(&dir.join(&f.name), f.contents.as_bytes())?;
    }
    super::warn(&format!("wrote {} files to {}", files.len(), dir.display()));
    Ok(())
}
